#pragma once
/// @file Splitting particles over ranks (issue 19): an order along a space-filling curve
/// cut into contiguous blocks (the distributed force's partition, local_part.hpp), and what
/// each rank of any partition needs from the others (its ghosts); `perinom check --ranks R`
/// reports it for a scene, beside PT-Scotch's partition of the bond graph
/// (distributed/graph_partition.hpp).
#include <cstddef>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/families.hpp"

namespace perinom {

/// The particles in the order of a Morton (Z-order) curve: positions quantised to 21 bits
/// per axis over the bounding box's longest side (one scale for all axes), bits
/// interleaved, sorted (ties by index).
std::vector<ParticleId> morton_order(const PointCloud& cloud);

/// One rank's share of a partition: the particles it owns and the other ranks' particles
/// its rows read: within one horizon (the families and dual families of its particles: G u
/// and G^T q), and within two (the assembled stabilization's and the Jacobian's pattern).
struct RankShare {
  std::size_t owned = 0, ghosts_one = 0, ghosts_two = 0;
};

/// The rank of each particle when `order` is cut into `ranks` contiguous blocks whose sizes
/// differ by at most one.
std::vector<int> block_ranks(const std::vector<ParticleId>& order, int ranks);

/// Each rank's share for the rank of each particle (`rank_of`, values in 0..ranks-1): its
/// ghosts from the families (bonds i -> j) and their transposes.
std::vector<RankShare> rank_shares(const Families& families, const std::vector<int>& rank_of, int ranks);

/// The same for `order` cut into blocks (block_ranks).
std::vector<RankShare> partition_shares(const Families& families, const std::vector<ParticleId>& order, int ranks);

}  // namespace perinom

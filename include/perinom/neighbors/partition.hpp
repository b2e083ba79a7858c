#pragma once
/// @file Splitting particles over ranks, as the distributed path (issue 19) will: an order
/// along a space-filling curve cut into contiguous blocks, and what each block would need
/// from the others (its ghosts). Nothing here is distributed; `perinom check --ranks R`
/// reports it for a scene.
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

/// `order` cut into `ranks` contiguous blocks whose sizes differ by at most one; the
/// ghosts of each from the families (bonds i -> j) and their transposes.
std::vector<RankShare> partition_shares(const Families& families, const std::vector<ParticleId>& order, int ranks);

}  // namespace perinom

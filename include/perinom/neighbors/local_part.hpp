#pragma once
/// @file One rank's particles in the distributed path (issue 19): the block of the curve
/// order it owns and the ghosts its rows read, as a cloud of their own on which the rank
/// builds its families and operators.
///
/// With radius families of horizon delta, a rank that holds every particle within 2 delta of
/// its owned ones has the whole family of each owned particle and of each near ghost (within
/// delta of an owned one: the rows its owned rows read through G^T and the stabilization). So
/// after one exchange of u, G u and the pointwise law on the owned and near rows, then G^T
/// and the stabilization on the owned rows, give the owned rows' force exactly
/// (CorrespondenceModel::limit_rows); the far ghosts only lend their u. Partial: every rank
/// still holds the whole cloud's positions to choose its part (24 bytes a particle in 3-D).
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/families.hpp"

namespace perinom {

struct LocalPart {
  /// The local particles' indices in the whole cloud: the `owned` first, in curve order,
  /// then the `near` ghosts, then the far ones, each group by position along the curve.
  std::vector<ParticleId> particles;
  /// The same particles' positions along the curve (the distributed numbering: rank r owns
  /// a contiguous range of it).
  std::vector<std::int64_t> global;
  std::size_t owned = 0;
  std::size_t near = 0;   ///< ghosts within one horizon of an owned particle
  std::size_t first = 0;  ///< the position along the curve of the first owned particle

  std::size_t ghosts() const { return particles.size() - owned; }
};

/// Rank `rank` of `ranks`: its block of `order` (blocks differ in size by at most one, as
/// partition_shares cuts them) and every other particle within two horizons of one of its
/// own (distances compared with a relative margin of 1e-9: a ghost too many, never one too few).
LocalPart local_part(const PointCloud& cloud, const std::vector<ParticleId>& order, int ranks, int rank,
                     double horizon);

/// The local index of each owned particle, by its index in the whole cloud.
std::unordered_map<ParticleId, std::size_t> owned_index(const LocalPart& part);

/// The whole cloud's families restricted to the part, in its local numbering: each local
/// particle keeps the members that are local (the owned and near ones keep all, when the part
/// was cut with a horizon at least the largest support) and its support. For families that a
/// search of the part alone could not reproduce: k-nearest ones, whose ties the k-d tree
/// breaks by the cloud it searches.
Families local_families(const Families& whole, const LocalPart& part);

}  // namespace perinom

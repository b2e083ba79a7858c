#pragma once
/// @file Supports for a free body: the resultant of its loads, and the fewest pins that stop
/// its rigid motion without holding it (a body loaded by balanced forces only).
#include <array>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/plate_cloud.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/models/loading.hpp"

namespace perinom {

/// The resultant of nodal forces f (N x d, N) about the cloud's volume centroid `about`:
/// force (N, d values) and moment (N m; one value in 2-D, three in 3-D). `force_scale` is
/// sum_i |f_i| (N) and `length` the diagonal of the particles' bounding box (m), the scales
/// a balance check compares with.
struct LoadResultant {
  std::array<double, 3> force{0, 0, 0}, moment{0, 0, 0}, about{0, 0, 0};
  double force_scale = 0.0;
  double length = 0.0;
  /// |force| and |moment| / length within `tolerance` * force_scale (true when unloaded).
  bool balanced(double tolerance) const;
};
LoadResultant load_resultant(const PointCloud& cloud, const std::vector<double>& force);
/// The same over the first `count` particles of `cloud` (a rank's owned ones; force holds at
/// least count x d values) about whole.about, with whole.length: `whole` is the whole cloud's
/// resultant (its about and length), so that the ranks' parts add up to it.
LoadResultant load_resultant_part(const PointCloud& cloud, const std::vector<double>& force, std::size_t count,
                                  const LoadResultant& whole);

/// One pinned particle and the components held (0 = x, 1 = y, 2 = z).
struct RigidBodyPin {
  ParticleId particle = 0;
  std::vector<int> components;
};

/// Pins that remove the d (d + 1) / 2 rigid modes and nothing more: the particle A nearest
/// the volume centroid held in every component; B, the particle nearest the far end of the
/// body's longest axis e1 through A, held across e1; in 3-D also C, nearest the far end of
/// the second-longest axis e2 through A, held along e3 = e1 x e2. So A stops translation, B
/// the rotations that move it across e1, C the rotation about e1. Throws InputError when the
/// pins do not determine the rigid modes (a body too small to hold them apart).
std::vector<RigidBodyPin> rigid_body_pins(const PointCloud& cloud);

/// A rigid motion no held dof resists: velocity t + w x (x - point). `turns`: a rotation
/// about the axis along w through `point` (with t along w, if any); otherwise a translation
/// along t (w zero). Unnormalised.
struct FreeRigidMotion {
  std::array<double, 3> translation{0, 0, 0}, rotation{0, 0, 0}, point{0, 0, 0};
  bool turns = false;
};

/// The rigid motions of the cloud that the loading's constraints leave at rest (a
/// face-located one read as it acts, at its face point): a basis of that space, empty when
/// the supports hold the body. A static balance needs it empty, or loads without force or
/// moment along what it holds. `within` (one flag a particle; empty: the whole cloud) asks
/// the same of a part, a piece a crack has cut off: the constraints on its particles only.
std::vector<FreeRigidMotion> free_rigid_motions(const PointCloud& cloud, const Loading& loading,
                                               const std::vector<std::uint8_t>& within = {});

/// The same for a thin plate (deflection w along z, one unknown a node): its rigid
/// deflections are a translation along z and turns about axes in its plane (returned as 3-D
/// motions, the plate in z = 0), held by the loading's w = 0 and by the supported edges'
/// ghosts (a clamped edge's mirror also holds the turn about that edge).
std::vector<FreeRigidMotion> free_plate_motions(const PlateCloud& plate, const Loading& loading);

}  // namespace perinom

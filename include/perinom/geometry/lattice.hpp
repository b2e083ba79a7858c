#pragma once
/// @file Regular (optionally jittered) lattices filling a box minus holes.
#include <array>
#include <cstdint>
#include <vector>

#include "perinom/geometry/point_cloud.hpp"

namespace perinom {

/// A hole cut out of the box: a circle (2-D), a sphere, or a cylinder along an axis (3-D).
struct Hole {
  enum class Shape { circle, sphere, cylinder };
  Shape shape = Shape::circle;
  std::array<double, 3> center{0, 0, 0};  ///< m
  double radius = 0.0;                    ///< m
  int axis = 2;                           ///< cylinder axis (0, 1, 2)

  /// True when the point p (dim coordinates) lies strictly inside the hole.
  bool contains(const double* p, int dim) const;
};

/// A box [min, max] with holes.
struct BoxGeometry {
  int dim = 3;
  std::array<double, 3> min{0, 0, 0};
  std::array<double, 3> max{0, 0, 0};
  std::vector<Hole> holes;
  double thickness = 1.0;  ///< out-of-plane thickness in 2-D (m)
};

/// Fills the box with a cell-centred lattice of nominal spacing dx: round(L/dx) cells per
/// axis, each axis' spacing adjusted so the cells tile the box exactly. Particles inside a hole
/// are dropped. jitter > 0 moves every particle by a uniform random offset in
/// [-jitter/2, jitter/2] * spacing per axis (seeded, reproducible).
PointCloud make_lattice(const BoxGeometry& box, double dx, double jitter = 0.0,
                        std::uint64_t seed = 1);

}  // namespace perinom

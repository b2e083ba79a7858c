#pragma once
/// @file The tightest concave bend of a body's surface (a hole, a notch's root, a fillet),
/// measured on its boundary facets in particle spacings: the stress at such a surface
/// converges with the spacings its radius spans.
#include <cstddef>
#include <limits>

#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/geometry/point_cloud.hpp"

namespace perinom {

struct SurfaceBend {
  double radius = std::numeric_limits<double>::infinity();  ///< m
  double spacings = std::numeric_limits<double>::infinity();  ///< radius over the particle spacing there
  std::size_t facet = 0;
  bool found() const { return spacings < std::numeric_limits<double>::infinity(); }
};

/// For each facet k and each of its 2 d nearest facets m (by centroid) that turns from it by
/// an angle theta between 0.1 and 75 degrees (a box's corner, 90, is not a bend; the chords
/// of a hole of 5, 72 each, are) towards the outside of the body (n_k . (c_m - c_k) > 0: a
/// concave surface, where the material wraps round the void), the radius of the circle through
/// both centroids with their normals, |c_m - c_k| / (2 sin(theta / 2)) (exact for the chords of
/// a circle or a cylinder; a pair offset along a cylinder's axis reads larger), over the
/// spacing there: (V_i / t)^(1/d) of the two facets' particles (t the 2-D thickness), or
/// `length_scale` when larger (the horizon's dx: a mesh refined round a hole smaller than dx
/// still sees it through a horizon of some dx, which averages over it). Returns
/// the smallest such ratio below `reach` (none: not found()). A convex surface (a cylinder's
/// outside) is not a bend here.
SurfaceBend tightest_concave_bend(const BoundaryFacets& facets, const PointCloud& cloud, double thickness_2d,
                                  double length_scale, double reach);

}  // namespace perinom

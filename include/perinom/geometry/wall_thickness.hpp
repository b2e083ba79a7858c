#pragma once
/// @file Where a body is thinnest, in particles across: from each boundary facet inward
/// along its normal to the facet that faces it across the material. It sees what a
/// bounding box cannot: a ligament between a hole and a face, the wall of a tube from a mesh.
#include <cstddef>
#include <limits>

#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/geometry/point_cloud.hpp"

namespace perinom {

/// The thinnest place found: `across` particle spacings between facet `facet` and the facet
/// `opposite` that faces it (infinity when none is found within the search's reach).
struct ThinSpot {
  double across = std::numeric_limits<double>::infinity();
  double thickness = 0.0;  ///< m, measured along facet's inward normal
  std::size_t facet = 0;
  std::size_t opposite = 0;
  bool found() const { return across < std::numeric_limits<double>::infinity(); }
};

/// The thinnest place of the body closed by `facets` among those thinner than `reach`
/// spacings. For each facet k the opposite facet is the nearest m inward along -n_k
/// (n_k . n_m < -0.5, so m faces back across the material, never across a void) whose
/// centroid is off the ray by less than the spacing there. A particle's spacing is
/// (V_i / t)^(1/d) (t the 2-D thickness, 1 in 3-D: the lattice spacing on a lattice, the
/// element size on a mesh), and `across` is the thickness over the mean spacing of the two
/// facets' particles: n for a lattice wall n particles thick. A facet grid of cell size the
/// largest spacing keeps the search at a few cells per step along each ray.
ThinSpot thinnest_wall(const BoundaryFacets& facets, const PointCloud& cloud, double thickness_2d, double reach);

}  // namespace perinom

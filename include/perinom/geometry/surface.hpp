#pragma once
/// @file Surface particles, their outward normals, and the band E near the surface
/// (THEORY sec. 5).
#include <cstdint>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/lattice.hpp"

namespace perinom {

/// Per-particle surface data of a box-minus-holes body.
/// normal_over_h[i*dim + a] = sum over the surfaces particle i lies on of n_a / h, with n the
/// unit outward normal of that surface and h the layer thickness (the spacing normal to a box
/// face; dx for a hole). Convex box corners and edges thus get the sum of their faces'
/// normals; interior particles get zero. A box minus holes has no concave corners.
/// in_band[i] is 1 when the particle lies within band_width of any surface (box faces and
/// holes), 0 otherwise.
struct Surface {
  std::vector<double> normal_over_h;
  std::vector<std::uint8_t> on_surface;
  std::vector<std::uint8_t> in_band;
  std::vector<ParticleId> band;      ///< ids with in_band = 1 (the subregion E)
  std::vector<ParticleId> interior;  ///< the others (the subregion D)
};

/// Surface particles are those within one spacing of a box face, or within one spacing dx
/// of a hole's boundary.
Surface find_surface(const BoxGeometry& box, const PointCloud& cloud, double band_width);

}  // namespace perinom

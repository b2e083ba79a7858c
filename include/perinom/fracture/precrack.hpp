#pragma once
/// @file Initial cracks (issue 17): a segment in 2-D, a planar rectangle in 3-D, cutting every
/// bond whose segment x_i - x_j crosses it. As seed 002 makes its notch, by the neighbour
/// list: no special lattice is needed.
#include <array>
#include <utility>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/families.hpp"

namespace perinom {

/// 2-D: the segment from `origin` to origin + edge1 (edge2 unused). 3-D: the rectangle
/// {origin + a edge1 + b edge2 : a, b in [0, 1]} (edge1 and edge2 need not be orthogonal,
/// but must not be parallel). Coordinates in metres.
struct Precrack {
  std::array<double, 3> origin{};
  std::array<double, 3> edge1{};
  std::array<double, 3> edge2{};
};

/// True when the segment p-q crosses the crack: p and q lie strictly on opposite sides of
/// its line (plane), and the crossing point lies on the crack, ends included. A bond with an
/// end on the crack's line or plane is not cut (put cracks between particle rows).
bool crosses(const Precrack& crack, int dim, const double* p, const double* q);

/// Every bond (i, j) of the families, i < j listed once whatever the direction it exists in,
/// that crosses one of the cracks. Throws std::invalid_argument for a degenerate crack
/// (zero length; in 3-D parallel or zero edges).
std::vector<std::pair<ParticleId, ParticleId>> bonds_crossing(const PointCloud& cloud, const Families& families,
                                                              const std::vector<Precrack>& cracks);

/// The particles lying on the crack (within 1e-9 of its length from its line or plane, their
/// foot on it): their bonds are not cut, and for a particle that rounding puts a hair off the
/// line the sign test decides its side, so a crack laid along a particle row cuts only some
/// bonds. Ascending. Throws std::invalid_argument as bonds_crossing does.
std::vector<ParticleId> particles_on(const PointCloud& cloud, const Precrack& crack);

}  // namespace perinom

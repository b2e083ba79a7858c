#pragma once
// A point file's volumes in other units than its positions, or 2-D volumes per unit thickness
// beside a geometry.thickness (or areas times the thickness without it), ran with exit 0: the
// mean spacing taken from the volumes was 32 times the particles' (thickness 0.001 m), and a
// line probe gathered the whole body (400 rows, not 80); in 3-D without facets nothing else
// checks the volumes at all. Run and check now compare each particle's volume with its
// distance to its nearest neighbour, and warn.
#include <string>

#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// The median over the particles of (V_i / t)^(1/d) / (distance to the nearest particle),
/// t = geometry.thickness in 2-D, 1 in 3-D: 1 on a lattice, about 1.1-1.5 on mesh centroids
/// and jittered clouds. Outside [1 / kPointVolumeFactor, kPointVolumeFactor] the warning.
inline constexpr double kPointVolumeFactor = 4.0;
double point_volume_ratio(const Problem& p);

/// "" or the warning (without a prefix) for a body from geometry.points whose
/// point_volume_ratio is outside the bounds.
std::string point_volume_warning(const Problem& p);

}  // namespace perinom::cli

#pragma once
// Whether a small-strain answer can be the body's: a result whose displacement gradient is
// not small (E in MPa with lengths in m, a load a thousand times too large) solves the linear
// equations exactly and means nothing; without this check it ended with exit 0 and a tip
// deflection two thousand times the beam's length.
#include <vector>

#include "perinom/io/json_writer.hpp"
#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// Beyond this |grad u| (Frobenius norm) at a particle, strains and rotations are not small.
inline constexpr double kSmallGradientLimit = 0.1;
/// Beyond this many thicknesses of deflection a plate stretches as it bends (membrane action).
inline constexpr double kSmallDeflectionLimit = 0.5;

/// The largest |grad u| over the particles that have lost no bond (a crack's opening is not a
/// strain), from the model's `displacement_gradient` output field; a thin plate (a `deflection`
/// field instead) has its largest |w| checked against its thickness. `kinematics:
/// finite_rotation` is not checked. Sets summary["largest_displacement_gradient"] = {value,
/// particle, position} (a plate: "largest_deflection", with over_thickness) and prints a
/// warning naming the particle when the limit is exceeded.
void check_small_strain(const Problem& p, const std::vector<double>& u, io::Json& summary);

}  // namespace perinom::cli

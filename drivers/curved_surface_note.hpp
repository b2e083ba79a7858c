#pragma once
// The stress at a curved surface converges with the particle spacings its radius spans: a
// plate's hole on body-fitted particles read its edge stress 11% low at 5 spacings with exit 0
// and no word (the thin-body note measures thickness, not curvature), and a hole smaller than a
// spacing read stresses of the wrong sign beside it. Run and check say so, and where.
#include <string>

#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// Below this many particle spacings in the radius of a concave bend, a body from files gets
/// the note (the hole plate's edge stress: -11% at 5 spacings, -2.1% at 10).
inline constexpr double kBendSpacings = 8.0;

/// "" or the note (without a prefix) for a correspondence body from geometry.mesh or
/// geometry.points whose facets bend concavely with a radius under kBendSpacings spacings
/// (tightest_concave_bend): the radius, where, and the measured hole-edge stress errors. A
/// lattice's holes have lattice_hole_note instead.
std::string curved_surface_note(const Problem& p);

}  // namespace perinom::cli

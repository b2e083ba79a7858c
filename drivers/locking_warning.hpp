#pragma once
// A nearly incompressible body few particles across locks in bending: the plane-strain
// cantilever at nu = 0.499, 4 particles thick, came out 70% too stiff with exit 0 (the
// consistent formulation's order-2 gradient is exact for linear fields only at surfaces,
// and the incompressible bending field is quadratic). Run and check say so before the solve,
// and say that a Drucker-Prager body's collapse load is over-stiff the same way (Prandtl's
// footing never levels off).
#include <string>

#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// lambda / mu from this up (nu = 0.45 in plane strain and 3-D; plane stress never reaches it).
inline constexpr double kLockingLambdaOverMu = 9.0;
/// Below this many particles across the warning is given (at 16, nu = 0.4999 was -1.2%).
inline constexpr int kLockingParticles = 16;

/// "" or the warning (without a prefix) for a correspondence body whose law has lambda / mu
/// >= kLockingLambdaOverMu and that is fewer than kLockingParticles across somewhere
/// (thinnest_place), unless the formulation is classical with operator_order 2 (which did
/// not lock in the measurements the warning quotes).
std::string locking_warning(const Problem& p);

/// "" or the note (without a prefix) for a Drucker-Prager correspondence body: a collapse by
/// a mechanism does not level off at its limit load (Prandtl's footing, measured).
std::string plastic_collapse_note(const Problem& p);

/// Prints, at the start of a run (serial, or the root of a distributed one), the point
/// volumes' warning (point_volume_note.hpp), the thin-body note, the thick-plate note, the lattice-hole note, the point-tie note, the locking warning, the plastic collapse note and the layer-support note
/// (layer_support_note.hpp) that apply to the problem
/// (`perinom: note:` / `perinom: warning:`).
void print_body_notes(const Problem& p);

}  // namespace perinom::cli

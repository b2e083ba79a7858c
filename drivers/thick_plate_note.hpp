#pragma once
// A thin plate as thick as it is wide (t = 1 m on a 0.5 m side) ran with exit 0 and reported
// the Kirchhoff deflection, which neglects the transverse shear a thick plate deforms by. Run
// and check say so when the plate is thicker than a tenth of its shorter side.
#include <string>

#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// From this ratio of the thickness to the plate's shorter side the note is given (the usual
/// bound of thin-plate theory).
inline constexpr double kThickPlateRatio = 0.1;

/// "" or the note (without a prefix) for a thin_plate scene with t / min(side) above
/// kThickPlateRatio.
std::string thick_plate_note(const Problem& p);

}  // namespace perinom::cli

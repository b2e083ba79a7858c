#pragma once
// A hole cut from the lattice (geometry.holes) is a staircase of cells: the displacement
// converges, the stress at its edge does not. A plate with a hole read sigma_xx 2.37 MPa at
// the hole's edge (Kirsch: about 3) at two spacings with exit 0 and no word; the figures were
// in docs/verification/README.md only. Run and check now say so.
#include <string>

#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// "" or the note (without a prefix) for a correspondence body with geometry.holes, with the
/// measured hole-edge stress errors of the scene's formulation.
std::string lattice_hole_note(const Problem& p);

}  // namespace perinom::cli

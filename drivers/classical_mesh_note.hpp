#pragma once
// The classical formulation on a body from files (a mesh or a point file): its surface
// effect, documented on the lattice, grows on an irregular cloud. A uniform strain on an
// L-shaped body (verification/formulation/classical_mesh.py) gave the moved faces' reactions
// -7.5% and -19% from triangles and -2.4% and -6.5% from quadrilaterals, particle stress up to
// 160% off near the surface, where a lattice box gave -1.9% and 40%; the consistent
// formulation reproduces the field to 1e-13 on all three. Run and check say so.
#include <string>

#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// "" or the note (without a prefix) for a correspondence body from a mesh or a point file
/// with the classical formulation.
std::string classical_mesh_note(const Problem& p);

}  // namespace perinom::cli

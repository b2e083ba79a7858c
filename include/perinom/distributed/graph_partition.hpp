#pragma once
/// @file PT-Scotch's partition of the bond graph (through PETSc's MatPartitioning), the
/// alternative to blocks of the Morton order (neighbors/partition.hpp) that issue 19 asks to
/// compare. Computed on one process; `perinom check --ranks R` reports both.
#include <vector>

#include "perinom/neighbors/families.hpp"

namespace perinom {

/// The rank (0..ranks-1) of each particle: PT-Scotch on the graph of the families made
/// symmetric (a bond in either direction is an edge). Throws InputError when this build has
/// no PETSc.
std::vector<int> scotch_partition(const Families& families, int ranks);

}  // namespace perinom

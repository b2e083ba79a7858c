#pragma once
// A precrack cuts the bonds that cross its line (plane); a bond with an end on the line is
// not cut (fracture/precrack.hpp), and a particle that rounding puts a hair off the line falls
// to one side or the other. A crack laid along a particle row therefore cut only some of the
// bonds across it, with exit 0 and no word. Run and check now say so.
#include <string>

#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// "" or the note (without a prefix) naming each precrack that passes through particles, how
/// many and the first of them.
std::string precrack_row_note(const Problem& p);

}  // namespace perinom::cli

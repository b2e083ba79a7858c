#pragma once
// A point region midway between particles takes the lowest-numbered (region.hpp): the notched
// beam's supports, midway between two columns at every spacing, sat half a spacing from their
// points, and until the ties were broken alike rounding put them on either side (its span
// 122.5 mm at dx 2.5 mm). Run and check now say where such a point region lands, a thin
// plate's point pressure included.
#include <string>

#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// "" or the note (without a prefix) naming each boundary item (the scene's and the stages')
/// whose point region is equally near several particles, the particle taken and how far it is.
std::string point_tie_note(const Problem& p);

}  // namespace perinom::cli

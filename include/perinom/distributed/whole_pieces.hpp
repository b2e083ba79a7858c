#pragma once
/// @file The pieces of the whole body over the ranks (issue 19): what body_pieces finds on a
/// serial run's bond graph, from each rank's owned families alone.
#include <cstdint>

#include "perinom/neighbors/families.hpp"
#include "perinom/neighbors/local_part.hpp"

namespace perinom {

/// How many pieces the whole cloud (`particles` in all) falls into, joined by the bonds of
/// every rank's owned rows (`families`: the part's, rows 0..part.owned-1 whole, a bond either
/// way), and `second`: the smallest particle not in particle 0's piece (-1 for one piece).
/// Collective: every rank calls it and gets the same answer.
struct WholePieces {
  std::int64_t count = 0;
  std::int64_t second = -1;
};
WholePieces whole_pieces(const LocalPart& part, const Families& families, std::size_t particles);

}  // namespace perinom

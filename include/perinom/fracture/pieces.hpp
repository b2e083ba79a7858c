#pragma once
/// @file The pieces a cracked body falls into: the connected parts of its live bond graph.
/// A load path that stops unbalanced asks which pieces its supports leave free.
#include <cstdint>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/neighbors/bond_graph.hpp"

namespace perinom {

/// piece[i] in 0 .. count-1 labels particle i's piece (joined by live bonds, either way);
/// -1 for a particle in `apart` (detached: it carries nothing, whatever bonds it keeps).
/// Pieces are numbered by their smallest particle.
struct Pieces {
  std::vector<std::int32_t> piece;
  std::int32_t count = 0;
};
Pieces body_pieces(const BondGraph& graph, const std::vector<ParticleId>& apart);

}  // namespace perinom

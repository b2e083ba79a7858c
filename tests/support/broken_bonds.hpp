#pragma once
// Broken bonds for the refresh tests: a random set of them, and the families without them.
#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "perinom/neighbors/families.hpp"

namespace perinom::test {

using Bond = std::pair<ParticleId, ParticleId>;

/// The families without the broken bonds (both directions), supports unchanged.
inline Families without(const Families& f, const std::set<Bond>& broken) {
  Families g;
  g.support = f.support;
  for (std::size_t i = 0; i < f.particles(); ++i) {
    for (Offset k = f.begin(i); k < f.end(i); ++k) {
      const ParticleId j = f.neighbors[k];
      if (!broken.count({static_cast<ParticleId>(i), j}) && !broken.count({j, static_cast<ParticleId>(i)}))
        g.neighbors.push_back(j);
    }
    g.offsets.push_back(static_cast<Offset>(g.neighbors.size()));
  }
  return g;
}

/// `count` distinct bonds of the families, drawn with a fixed seed.
inline std::vector<Bond> random_bonds(const Families& f, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::set<Bond> chosen;
  std::vector<Bond> out;
  while (out.size() < count) {
    const std::size_t i = rng() % f.particles();
    if (f.end(i) == f.begin(i)) continue;
    const ParticleId j = f.neighbors[f.begin(i) + static_cast<Offset>(rng() % (f.end(i) - f.begin(i)))];
    const Bond b{std::min<ParticleId>(i, j), std::max<ParticleId>(i, j)};
    if (chosen.insert(b).second) out.push_back({static_cast<ParticleId>(i), j});
  }
  return out;
}

}  // namespace perinom::test

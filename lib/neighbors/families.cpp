#include "perinom/neighbors/families.hpp"

namespace perinom {

DualSupport dual_support(const Families& f) {
  const std::size_t n = f.particles();
  DualSupport t;
  t.offsets.assign(n + 1, 0);
  for (const ParticleId j : f.neighbors) ++t.offsets[j + 1];
  for (std::size_t i = 0; i < n; ++i) t.offsets[i + 1] += t.offsets[i];
  t.neighbors.resize(f.bonds());
  t.bond.resize(f.bonds());
  std::vector<Offset> next(t.offsets.begin(), t.offsets.end() - 1);
  // Rows are visited in increasing order, so each dual row comes out sorted by id.
  for (std::size_t i = 0; i < n; ++i)
    for (Offset k = f.begin(i); k < f.end(i); ++k) {
      const Offset slot = next[f.neighbors[k]]++;
      t.neighbors[slot] = static_cast<ParticleId>(i);
      t.bond[slot] = k;
    }
  return t;
}

std::size_t memory_bytes(const Families& f) {
  return f.offsets.size() * sizeof(Offset) + f.neighbors.size() * sizeof(ParticleId) +
         f.support.size() * sizeof(double);
}

}  // namespace perinom

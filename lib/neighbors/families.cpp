#include "perinom/neighbors/families.hpp"

#include <string>

#include "perinom/core/error.hpp"

namespace perinom {

void check_families(const Families& f, std::size_t particles) {
  const auto text = [](auto v) { return std::to_string(v); };
  if (f.offsets.empty() || f.particles() != particles)
    throw InputError("Families: rows for " + text(f.offsets.empty() ? 0 : f.particles()) + " particles on a cloud of " +
                     text(particles) + " (families built for another cloud?)");
  if (f.offsets.front() != 0 || f.offsets.back() != static_cast<Offset>(f.bonds()))
    throw InputError("Families::offsets: run from " + text(f.offsets.front()) + " to " + text(f.offsets.back()) +
                     ", not from 0 to the " + text(f.bonds()) + " neighbours");
  if (!f.support.empty() && f.support.size() != particles)
    throw InputError("Families::support: " + text(f.support.size()) + " radii for " + text(particles) + " particles");
  for (std::size_t i = 0; i < particles; ++i)
    if (f.end(i) < f.begin(i)) throw InputError("Families::offsets: row " + text(i) + " ends before it begins");
  for (std::size_t i = 0; i < particles; ++i)
    for (Offset k = f.begin(i); k < f.end(i); ++k) {
      const ParticleId j = f.neighbors[k];
      if (j < 0 || static_cast<std::size_t>(j) >= particles)
        throw InputError("Families::neighbors: particle " + text(i) + " has neighbour " + text(j) + ", beyond the " +
                         text(particles) + " particles of the cloud");
      if (static_cast<std::size_t>(j) == i)
        throw InputError("Families::neighbors: particle " + text(i) + " is its own neighbour");
    }
}

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

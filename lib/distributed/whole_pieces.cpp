#include "perinom/distributed/whole_pieces.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

#include "perinom/distributed/ranks.hpp"

namespace perinom {

namespace {

std::size_t root_of(std::vector<std::size_t>& up, std::size_t i) {
  while (up[i] != i) i = up[i] = up[up[i]];
  return i;
}

}  // namespace

WholePieces whole_pieces(const LocalPart& part, const Families& families, std::size_t particles) {
  // Every particle carries the smallest particle it is known to be joined to, held negated
  // on every rank so that the largest over the ranks spreads the smallest. A round joins
  // each rank's local pieces (its owned rows' bonds) under their smallest label, then takes
  // the smallest over the ranks; a piece crossing k ranks settles within k + 1 rounds.
  const std::size_t local = part.particles.size();
  std::vector<std::size_t> up(local);
  std::iota(up.begin(), up.end(), std::size_t(0));
  for (std::size_t i = 0; i < part.owned; ++i)
    for (Offset k = families.begin(i); k < families.end(i); ++k) {
      const std::size_t a = root_of(up, i), b = root_of(up, std::size_t(families.neighbors[k]));
      if (a != b) up[std::max(a, b)] = std::min(a, b);
    }
  std::vector<double> label(particles);
  for (std::size_t g = 0; g < particles; ++g) label[g] = -double(g);
  std::vector<double> smallest(local);
  for (bool changed = true; changed;) {
    std::fill(smallest.begin(), smallest.end(), -double(particles));
    for (std::size_t i = 0; i < local; ++i) {
      double& s = smallest[root_of(up, i)];
      s = std::max(s, label[std::size_t(part.particles[i])]);
    }
    double moved = 0.0;
    for (std::size_t i = 0; i < local; ++i) {
      double& l = label[std::size_t(part.particles[i])];
      const double s = smallest[root_of(up, i)];
      if (s > l) l = s, moved = 1.0;
    }
    max_over_ranks(label.data(), int(particles));
    changed = max_over_ranks(moved) > 0.0;
  }
  WholePieces w;
  for (std::size_t g = 0; g < particles; ++g)
    if (label[g] == -double(g)) {
      ++w.count;
      if (g > 0 && w.second < 0) w.second = std::int64_t(g);
    }
  return w;
}

}  // namespace perinom

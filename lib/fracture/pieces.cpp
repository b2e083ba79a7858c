#include "perinom/fracture/pieces.hpp"

#include <numeric>

namespace perinom {

Pieces body_pieces(const BondGraph& graph, const std::vector<ParticleId>& apart) {
  const std::size_t n = graph.rows();
  std::vector<std::uint8_t> out(n, 0);
  for (const ParticleId i : apart) out[i] = 1;
  // Union-find with path halving; a root is its piece's smallest particle.
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (out[i]) continue;
    graph.for_each_live(i, [&](Offset, ParticleId j) {
      if (static_cast<std::size_t>(j) >= n || out[j]) return;
      const std::size_t a = root(i), b = root(j);
      if (a < b) parent[b] = a;
      else if (b < a) parent[a] = b;
    });
  }
  Pieces p;
  p.piece.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (out[i]) continue;
    const std::size_t r = root(i);
    if (r == i) p.piece[i] = p.count++;
    else p.piece[i] = p.piece[r];
  }
  return p;
}

}  // namespace perinom

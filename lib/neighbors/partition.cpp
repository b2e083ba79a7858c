#include "perinom/neighbors/partition.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace perinom {
namespace {

/// The 21 low bits of v spread to every third bit (3-D Morton code); in 2-D every other.
std::uint64_t spread(std::uint64_t v, int dim) {
  std::uint64_t out = 0;
  for (int b = 0; b < 21; ++b) out |= ((v >> b) & 1u) << (b * dim);
  return out;
}

}  // namespace

std::vector<ParticleId> morton_order(const PointCloud& cloud) {
  const int d = cloud.dim;
  const std::size_t n = cloud.size();
  std::vector<double> lo(d, 0.0), hi(d, 0.0);
  for (int a = 0; a < d && n > 0; ++a) {
    lo[a] = hi[a] = cloud.x[a];
    for (std::size_t i = 0; i < n; ++i) lo[a] = std::min(lo[a], cloud.x[i * d + a]), hi[a] = std::max(hi[a], cloud.x[i * d + a]);
  }
  // One scale for every axis (the longest span), so a slender body is cut across its
  // length: per-axis scales would make the curve's first cut run along it.
  double span = 0.0;
  for (int a = 0; a < d; ++a) span = std::max(span, hi[a] - lo[a]);
  std::vector<std::pair<std::uint64_t, ParticleId>> keyed(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t key = 0;
    for (int a = 0; a < d; ++a) {
      const double t = span > 0.0 ? (cloud.x[i * d + a] - lo[a]) / span : 0.0;
      key |= spread(static_cast<std::uint64_t>(t * ((1u << 21) - 1)), d) << a;
    }
    keyed[i] = {key, static_cast<ParticleId>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<ParticleId> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = keyed[k].second;
  return order;
}

std::vector<int> block_ranks(const std::vector<ParticleId>& order, int ranks) {
  const std::size_t n = order.size();
  if (ranks < 1) throw std::invalid_argument("block_ranks: ranks < 1");
  std::vector<int> rank_of(n, 0);
  for (int r = 0; r < ranks; ++r)
    for (std::size_t k = n * r / ranks; k < n * (r + 1) / ranks; ++k) rank_of[order[k]] = r;
  return rank_of;
}

std::vector<RankShare> partition_shares(const Families& f, const std::vector<ParticleId>& order, int ranks) {
  if (order.size() != f.particles()) throw std::invalid_argument("partition_shares: an order of another size");
  return rank_shares(f, block_ranks(order, ranks), ranks);
}

std::vector<RankShare> rank_shares(const Families& f, const std::vector<int>& rank_of, int ranks) {
  const std::size_t n = f.particles();
  if (ranks < 1 || rank_of.size() != n) throw std::invalid_argument("rank_shares: ranks < 1 or ranks for another size");
  for (const int r : rank_of)
    if (r < 0 || r >= ranks) throw std::invalid_argument("rank_shares: a rank outside 0..ranks-1");
  std::vector<std::vector<ParticleId>> members(static_cast<std::size_t>(ranks));
  for (std::size_t i = 0; i < n; ++i) members[static_cast<std::size_t>(rank_of[i])].push_back(static_cast<ParticleId>(i));
  // Each particle's readers' neighbours: its family and its dual family (bonds j -> i).
  const DualSupport dual = dual_support(f);
  const auto visit = [&](std::size_t i, auto&& fn) {
    for (Offset b = f.begin(i); b < f.end(i); ++b) fn(f.neighbors[b]);
    for (Offset b = dual.offsets[i]; b < dual.offsets[i + 1]; ++b) fn(dual.neighbors[b]);
  };
  std::vector<RankShare> shares(static_cast<std::size_t>(ranks));
  std::vector<int> mark(n, -1);  // the rank (and pass) that counted a particle last
  std::vector<ParticleId> ring;
  for (int r = 0; r < ranks; ++r) {
    RankShare& s = shares[static_cast<std::size_t>(r)];
    s.owned = members[static_cast<std::size_t>(r)].size();
    ring.clear();
    for (const ParticleId i : members[static_cast<std::size_t>(r)])
      visit(i, [&](ParticleId j) {
        if (rank_of[j] != r && mark[j] != 2 * r) mark[j] = 2 * r, ring.push_back(j);
      });
    s.ghosts_one = ring.size();
    std::size_t two = 0;
    for (const ParticleId g : ring)
      visit(g, [&](ParticleId j) {
        if (rank_of[j] != r && mark[j] != 2 * r && mark[j] != 2 * r + 1) mark[j] = 2 * r + 1, ++two;
      });
    s.ghosts_two = s.ghosts_one + two;
  }
  return shares;
}

}  // namespace perinom

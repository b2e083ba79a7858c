// The partition the distributed path will use: a Morton order cut into blocks, and each
// block's ghosts, against a count by brute force.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "../support/clouds.hpp"
#include "perinom/neighbors/partition.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

namespace {

/// Ghosts of the particles in [first, last) of order by sets: the other ranks' particles one
/// bond away (either direction), and two.
std::pair<std::size_t, std::size_t> brute_ghosts(const Families& f, const std::vector<ParticleId>& order, std::size_t first,
                                                 std::size_t last) {
  const std::set<ParticleId> own(order.begin() + first, order.begin() + last);
  std::vector<std::set<ParticleId>> near(f.particles());
  for (std::size_t i = 0; i < f.particles(); ++i)
    for (Offset b = f.begin(i); b < f.end(i); ++b) near[i].insert(f.neighbors[b]), near[f.neighbors[b]].insert(ParticleId(i));
  std::set<ParticleId> one, two;
  for (const ParticleId i : own)
    for (const ParticleId j : near[i])
      if (!own.count(j)) one.insert(j);
  two = one;
  for (const ParticleId g : one)
    for (const ParticleId j : near[g])
      if (!own.count(j)) two.insert(j);
  return {one.size(), two.size()};
}

}  // namespace

TEST_CASE("a Morton partition's blocks own every particle once and count their ghosts", "[neighbors][partition]") {
  for (const int dim : {2, 3}) {
    INFO("dimension " << dim);
    const PointCloud cloud = dim == 2 ? test::lattice(2, 17, 0.2, 11) : test::lattice(3, 8, 0.2, 12);
    const Families f = radius_families(cloud, 3.015);
    const std::vector<ParticleId> order = morton_order(cloud);
    std::vector<ParticleId> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 0; k < sorted.size(); ++k) REQUIRE(sorted[k] == ParticleId(k));
    CHECK(partition_shares(f, order, 1)[0].ghosts_one == 0);
    for (const int ranks : {2, 3, 7}) {
      const auto shares = partition_shares(f, order, ranks);
      std::size_t owned = 0;
      for (int r = 0; r < ranks; ++r) {
        const std::size_t first = cloud.size() * r / ranks, last = cloud.size() * (r + 1) / ranks;
        const auto [one, two] = brute_ghosts(f, order, first, last);
        CHECK(shares[r].owned == last - first);
        CHECK(shares[r].ghosts_one == one);
        CHECK(shares[r].ghosts_two == two);
        owned += shares[r].owned;
      }
      CHECK(owned == cloud.size());
    }
  }
}

TEST_CASE("a Morton order keeps blocks compact", "[neighbors][partition]") {
  // On a 40 x 40 lattice, 4 Morton blocks are the 4 quadrants: each needs the 3 layers along
  // its two inner edges and the 4 particles of the opposite quadrant within 3.015 of its
  // corner (3 x 20 + 3 x 20 + 4 = 124 ghosts within one horizon).
  const PointCloud cloud = test::lattice(2, 40, 0.0, 1);
  const Families f = radius_families(cloud, 3.015);
  const auto shares = partition_shares(f, morton_order(cloud), 4);
  for (const RankShare& s : shares) CHECK(s.ghosts_one == 124);
}

TEST_CASE("any partition's ghosts are counted as for the Morton blocks", "[neighbors][partition]") {
  // rank_shares for an arbitrary assignment (round robin: every rank's ghosts are nearly
  // everyone) against the brute-force sets.
  const PointCloud cloud = test::lattice(2, 13, 0.2, 4);
  const Families f = radius_families(cloud, 3.015);
  const int ranks = 3;
  std::vector<int> rank_of(cloud.size());
  std::vector<ParticleId> order;
  for (int r = 0; r < ranks; ++r)
    for (std::size_t i = 0; i < cloud.size(); ++i)
      if (int(i % ranks) == r) rank_of[i] = r, order.push_back(ParticleId(i));
  const auto shares = rank_shares(f, rank_of, ranks);
  std::size_t first = 0;
  for (int r = 0; r < ranks; ++r) {
    const auto [one, two] = brute_ghosts(f, order, first, first + shares[r].owned);
    CHECK(shares[r].ghosts_one == one);
    CHECK(shares[r].ghosts_two == two);
    first += shares[r].owned;
  }
  CHECK(first == cloud.size());
  CHECK_THROWS_AS(rank_shares(f, std::vector<int>(cloud.size(), ranks), ranks), std::invalid_argument);
}

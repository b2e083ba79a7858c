// PT-Scotch's partition of the bond graph (through PETSc): every particle gets one of the
// ranks, the parts are balanced, and its ghosts are not far above the Morton blocks' on a
// cube (where the curve's blocks are already near-optimal).
#include <catch2/catch.hpp>

#include <algorithm>

#include "../support/clouds.hpp"
#include "perinom/core/error.hpp"
#include "perinom/distributed/graph_partition.hpp"
#include "perinom/neighbors/partition.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/solvers/petsc.hpp"

using namespace perinom;

TEST_CASE("PT-Scotch partitions the bond graph into balanced parts", "[distributed][partition][petsc]") {
  const PointCloud cloud = test::lattice(3, 12, 0.2, 8);
  const Families f = radius_families(cloud, 3.015);
  if (!petsc_available()) {
    CHECK_THROWS_AS(scotch_partition(f, 2), InputError);
    return;
  }
  for (const int ranks : {1, 2, 3, 8}) {
    INFO(ranks << " ranks");
    const std::vector<int> rank_of = scotch_partition(f, ranks);
    REQUIRE(rank_of.size() == cloud.size());
    std::vector<std::size_t> count(static_cast<std::size_t>(ranks), 0);
    for (const int r : rank_of) {
      REQUIRE(r >= 0);
      REQUIRE(r < ranks);
      ++count[static_cast<std::size_t>(r)];
    }
    const double mean = double(cloud.size()) / ranks;
    CHECK(double(*std::max_element(count.begin(), count.end())) <= 1.05 * mean + 1.0);
    CHECK(double(*std::min_element(count.begin(), count.end())) >= 0.95 * mean - 1.0);
    // A graph partitioner minimises the cut: its ghosts are not above the curve's by much
    // (the curve's octants at 8 ranks are already near-optimal cubes).
    std::size_t scotch = 0, morton = 0;
    for (const RankShare& s : rank_shares(f, rank_of, ranks)) scotch += s.ghosts_one;
    for (const RankShare& s : partition_shares(f, morton_order(cloud), ranks)) morton += s.ghosts_one;
    CHECK(double(scotch) <= 1.25 * double(morton));
  }
}

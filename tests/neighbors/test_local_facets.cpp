// A rank's share of the boundary facets (local_facets): the facets of its owned and near
// particles, each the whole body's facet with its particle renumbered locally, and every
// group renumbered into them, so a rank's face supports and facet loads act where a serial
// run's do (the MPI tests run whole scenes on it).
#include <catch2/catch.hpp>

#include <set>

#include "perinom/distributed/local_facets.hpp"
#include "perinom/geometry/lattice.hpp"
#include "perinom/neighbors/partition.hpp"

using namespace perinom;

TEST_CASE("local_facets keeps the facets of a part's evaluated rows, renumbered, and its share of every group",
          "[distributed]") {
  BoxGeometry box;
  box.dim = 2;
  box.max = {0.02, 0.01, 0.0};
  const PointCloud cloud = make_lattice(box, 0.001, 0.0, 1);
  const BoundaryFacets whole = lattice_facets(box, cloud);
  // Two groups: the left side's facets and every other facet, as a mesh's would be.
  std::vector<FacetGroup> groups{{"left", {}}, {"rest", {}}};
  for (std::size_t k = 0; k < whole.size(); ++k) groups[whole.side[k] == 0 ? 0 : 1].facets.push_back(k);
  const std::vector<ParticleId> order = morton_order(cloud);
  const int ranks = 3;
  std::vector<int> claimed(whole.size(), 0);
  for (int rank = 0; rank < ranks; ++rank) {
    const LocalPart part = local_part(cloud, order, ranks, rank, 3.015 * 0.001);
    const std::size_t rows = part.owned + part.near;
    const LocalFacets mine = local_facets(whole, groups, part, rows);
    REQUIRE(mine.local_of.size() == whole.size());
    REQUIRE(mine.groups.size() == groups.size());
    std::size_t kept = 0;
    for (std::size_t k = 0; k < whole.size(); ++k) {
      const std::int64_t l = mine.local_of[k];
      // Kept exactly when its particle is one of the evaluated rows.
      bool evaluated = false;
      for (std::size_t p = 0; p < rows; ++p) evaluated = evaluated || part.particles[p] == whole.particle[k];
      CHECK((l >= 0) == evaluated);
      if (l < 0) continue;
      ++kept;
      const auto i = std::size_t(l);
      CHECK(part.particles[std::size_t(mine.facets.particle[i])] == whole.particle[k]);
      CHECK(mine.facets.area[i] == whole.area[k]);
      CHECK(mine.facets.side[i] == whole.side[k]);
      for (int a = 0; a < 2; ++a) {
        CHECK(mine.facets.normal[i * 2 + a] == whole.normal[k * 2 + a]);
        CHECK(mine.facets.centroid[i * 2 + a] == whole.centroid[k * 2 + a]);
      }
      // An owned particle's facet is this rank's alone.
      for (std::size_t p = 0; p < part.owned; ++p)
        if (part.particles[p] == whole.particle[k]) ++claimed[k];
    }
    CHECK(mine.facets.size() == kept);
    // Each group: exactly its kept facets, in local numbering.
    for (std::size_t g = 0; g < groups.size(); ++g) {
      std::set<std::int64_t> expected, got;
      for (const std::size_t k : groups[g].facets)
        if (mine.local_of[k] >= 0) expected.insert(mine.local_of[k]);
      for (const std::size_t l : mine.groups[g].facets) got.insert(std::int64_t(l));
      CHECK(got == expected);
      CHECK(mine.groups[g].name == groups[g].name);
    }
  }
  for (std::size_t k = 0; k < whole.size(); ++k) CHECK(claimed[k] == 1);  // every facet owned once
}

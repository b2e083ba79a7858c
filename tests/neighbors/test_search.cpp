#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "../support/clouds.hpp"
#include "perinom/core/error.hpp"
#include "perinom/geometry/lattice.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

namespace {

/// A random cloud in the unit box (not a lattice, so distances are all distinct).
PointCloud random_cloud(int dim, std::size_t n) {
  PointCloud c;
  c.dim = dim;
  c.x = test::random_field(n * dim, 1.0, 11);
  c.volume.assign(n, 1.0);
  c.spacing.assign(dim, 1.0);
  return c;
}

std::vector<double> distances(const PointCloud& c, std::size_t i) {
  std::vector<double> r;
  for (std::size_t j = 0; j < c.size(); ++j) {
    if (j == i) continue;
    double r2 = 0.0;
    for (int a = 0; a < c.dim; ++a) r2 += std::pow(c.x[j * c.dim + a] - c.x[i * c.dim + a], 2);
    r.push_back(std::sqrt(r2));
  }
  std::sort(r.begin(), r.end());
  return r;
}

}  // namespace

TEST_CASE("radius search equals brute force on random clouds", "[neighbors]") {
  for (int dim : {2, 3}) {
    const PointCloud c = random_cloud(dim, 700);
    const double delta = dim == 2 ? 0.2 : 0.4;  // about 20 neighbours in [-1, 1]^d
    const Families fast = radius_families(c, delta);
    const Families slow = test::brute_force_radius(c, delta);
    CHECK(fast.offsets == slow.offsets);
    CHECK(fast.neighbors == slow.neighbors);
    CHECK(fast.bonds() > 10 * c.size());
  }
}

TEST_CASE("radius search equals brute force on a lattice at horizon ratio 3.015", "[neighbors]") {
  const PointCloud c = test::lattice(3, 9, 0.0);
  const Families fast = radius_families(c, 3.015);
  CHECK(fast.neighbors == test::brute_force_radius(c, 3.015).neighbors);
  // An interior particle of a simple-cubic lattice has 122 neighbours within 3.015.
  std::size_t most = 0;
  for (std::size_t i = 0; i < c.size(); ++i) most = std::max<std::size_t>(most, fast.end(i) - fast.begin(i));
  CHECK(most == 122);
}

TEST_CASE("a whole-number horizon ratio keeps the lattice neighbours at exactly delta, in any unit of length",
          "[neighbors]") {
  // At ratio 3.0 the neighbours at exactly 3 dx were kept or dropped by the rounding of their
  // coordinates: a symmetric plate with a hole answered 3.7% apart at mirrored particles, and
  // the same plate in mm differed by 1.4% from the one in m.
  for (const double unit : {1.0, 1000.0, 1e-3}) {
    INFO("unit " << unit);
    BoxGeometry box;
    box.dim = 2;
    box.min = {0.1 * unit, 0.03 * unit, 0.0};
    box.max = {0.2 * unit, 0.13 * unit, 0.0};
    const double dx = 0.0025 * unit;
    const PointCloud c = make_lattice(box, dx);
    const Families f = radius_families(c, 3.0 * dx);
    std::size_t interior = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double x = c.x[2 * i], y = c.x[2 * i + 1];
      if (x < box.min[0] + 3 * dx || x > box.max[0] - 3 * dx || y < box.min[1] + 3 * dx || y > box.max[1] - 3 * dx)
        continue;
      ++interior;
      REQUIRE(f.end(i) - f.begin(i) == 28);  // the lattice points of the disc of radius 3 but the centre
    }
    CHECK(interior == 34 * 34);
  }
}

TEST_CASE("k-nearest search equals brute force", "[neighbors]") {
  for (int dim : {2, 3}) {
    const PointCloud c = random_cloud(dim, 500);
    const int k = dim == 2 ? 14 : 33;
    const Families f = knn_families(c, k);
    for (std::size_t i = 0; i < c.size(); ++i) {
      REQUIRE(f.end(i) - f.begin(i) == k);
      const auto r = distances(c, i);
      // The k-th distance is the support, and every neighbour lies within it.
      CHECK(f.support[i] == Approx(r[k - 1]).epsilon(1e-14));
      for (Offset m = f.begin(i); m < f.end(i); ++m) {
        const std::size_t j = f.neighbors[m];
        double r2 = 0.0;
        for (int a = 0; a < dim; ++a) r2 += std::pow(c.x[j * dim + a] - c.x[i * dim + a], 2);
        CHECK(std::sqrt(r2) <= r[k - 1] * (1 + 1e-14));
        CHECK(j != i);
      }
    }
  }
}

TEST_CASE("the dual-support of k-nearest families lists exactly the bonds pointing in", "[neighbors]") {
  const PointCloud c = random_cloud(2, 300);
  const Families f = knn_families(c, 10);
  const DualSupport t = dual_support(f);
  std::size_t unequal = 0;
  for (std::size_t i = 0; i < f.particles(); ++i) {
    for (Offset s = t.offsets[i]; s < t.offsets[i + 1]; ++s) {
      CHECK(f.neighbors[t.bond[s]] == static_cast<ParticleId>(i));
      const std::size_t j = t.neighbors[s];
      CHECK(t.bond[s] >= f.begin(j));
      CHECK(t.bond[s] < f.end(j));
    }
    unequal += (t.offsets[i + 1] - t.offsets[i]) != (f.end(i) - f.begin(i));
  }
  CHECK(t.offsets.back() == static_cast<Offset>(f.bonds()));
  CHECK(unequal > 0);  // supports really differ: the dual-support is not the family
}

TEST_CASE("radius search on an empty cloud gives empty families", "[neighbors]") {
  PointCloud c;
  c.dim = 2;
  const Families f = radius_families(c, 0.3);
  CHECK(f.particles() == 0);
  CHECK(f.bonds() == 0);
}

TEST_CASE("the neighbour searches refuse a cloud whose x does not fit its size and dim", "[neighbors]") {
  PointCloud c = test::lattice(2, 6, 0.0);
  c.x.resize(10);
  REQUIRE_THROWS_WITH(radius_families(c, 1.5), Catch::Contains("PointCloud::x holds 10 coordinates for 36"));
  REQUIRE_THROWS_WITH(knn_families(c, 8), Catch::Contains("PointCloud::x holds 10 coordinates for 36"));
  PointCloud d4 = test::lattice(2, 6, 0.0);
  d4.dim = 4;
  REQUIRE_THROWS_WITH(radius_families(d4, 1.5), Catch::Contains("PointCloud::dim = 4"));
  REQUIRE_THROWS_WITH(knn_families(d4, 8), Catch::Contains("PointCloud::dim = 4"));
}

TEST_CASE("the neighbour searches refuse a particle at a coordinate that is not finite, naming it", "[neighbors]") {
  PointCloud c = test::lattice(2, 6, 0.0);
  c.x[2 * 2 + 1] = std::nan("");
  REQUIRE_THROWS_AS(radius_families(c, 1.5), InputError);
  REQUIRE_THROWS_WITH(radius_families(c, 1.5), Catch::Contains("particle 2 at (2.5, nan)"));
  c.x[2 * 2 + 1] = INFINITY;
  REQUIRE_THROWS_WITH(knn_families(c, 8), Catch::Contains("particle 2 at (2.5, inf)"));
}

TEST_CASE("the neighbour searches refuse a volume that is not positive, naming the particle", "[neighbors]") {
  PointCloud c = test::lattice(3, 3, 0.0);
  c.volume[5] = -1.0;
  REQUIRE_THROWS_WITH(radius_families(c, 1.5), Catch::Contains("PointCloud::volume: particle 5 has volume -1"));
}

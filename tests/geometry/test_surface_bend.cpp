// The tightest concave bend of a surface, in spacings, from its facets: the chords of a hole
// give its radius, those of a body's round outside give none (convex), and a box's corners
// give none (a corner is not a bend).
#include <catch2/catch.hpp>

#include <cmath>

#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/geometry/lattice.hpp"
#include "perinom/geometry/surface_bend.hpp"

using namespace perinom;

namespace {

// n chords of a circle of radius r round the origin, each facet owned by a particle of volume
// h^2 (spacing h); normals pointing to the centre (a hole: the void inside) or away from it.
void add_circle(BoundaryFacets& f, PointCloud& c, int n, double r, double h, bool hole) {
  const double pi = std::acos(-1.0);
  for (int k = 0; k < n; ++k) {
    const double a0 = 2 * pi * k / n, a1 = 2 * pi * (k + 1) / n, am = 0.5 * (a0 + a1);
    const double cx = 0.5 * r * (std::cos(a0) + std::cos(a1)), cy = 0.5 * r * (std::sin(a0) + std::sin(a1));
    const double sign = hole ? -1.0 : 1.0;
    f.particle.push_back(c.size());
    f.area.push_back(2 * r * std::sin(pi / n));
    f.normal.insert(f.normal.end(), {sign * std::cos(am), sign * std::sin(am)});
    f.centroid.insert(f.centroid.end(), {cx, cy});
    f.side.push_back(0);
    c.x.insert(c.x.end(), {cx * (1 + sign * 0.01), cy * (1 + sign * 0.01)});
    c.volume.push_back(h * h);
  }
}

}  // namespace

TEST_CASE("the chords of a hole give its radius in spacings, a round outside and a box give no bend", "[geometry]") {
  for (const int n : {5, 16, 64}) {
    BoundaryFacets f;
    f.dim = 2;
    PointCloud c;
    c.dim = 2;
    add_circle(f, c, n, 0.01, 0.002, true);
    INFO(n << " chords");
    const SurfaceBend bend = tightest_concave_bend(f, c, 1.0, 0.0, 100.0);
    REQUIRE(bend.found());
    // The circle through two neighbouring chords' midpoints with their normals: r cos(pi / n).
    CHECK(bend.radius == Approx(0.01 * std::cos(std::acos(-1.0) / n)).epsilon(1e-12));
    CHECK(bend.spacings == Approx(bend.radius / 0.002).epsilon(1e-12));
    // dx larger than the particles' spacing measures the radius in dx; a reach below it finds none.
    CHECK(tightest_concave_bend(f, c, 1.0, 0.004, 100.0).spacings == Approx(bend.radius / 0.004).epsilon(1e-12));
    CHECK_FALSE(tightest_concave_bend(f, c, 1.0, 0.0, 0.9 * bend.spacings).found());
    // The same chords as a disc's outside: convex, no bend.
    BoundaryFacets outside;
    outside.dim = 2;
    PointCloud disc;
    disc.dim = 2;
    add_circle(outside, disc, n, 0.01, 0.002, false);
    CHECK_FALSE(tightest_concave_bend(outside, disc, 1.0, 0.0, 100.0).found());
  }
  for (const int dim : {2, 3}) {
    BoxGeometry box;
    box.dim = dim;
    box.max = {10.0, 4.0, dim == 3 ? 3.0 : 0.0};
    const PointCloud c = make_lattice(box, 1.0);
    CHECK_FALSE(tightest_concave_bend(lattice_facets(box, c), c, box.thickness, 0.0, 100.0).found());
  }
}

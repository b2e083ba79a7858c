// Where a body is thinnest, in particles across, from its boundary facets: a slab, a ligament
// between a hole and a face (which a bounding box cannot see), a rotated strip (normals off
// the axes), and a squat body with no place thinner than the reach.
#include <catch2/catch.hpp>

#include <cmath>

#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/geometry/lattice.hpp"
#include "perinom/geometry/wall_thickness.hpp"

using namespace perinom;

namespace {

BoxGeometry box_of(int dim, std::array<double, 3> max) {
  BoxGeometry box;
  box.dim = dim;
  box.max = max;
  return box;
}

}  // namespace

TEST_CASE("a slab n particles thick is n across, measured between its two faces", "[geometry]") {
  for (const int dim : {2, 3}) {
    for (const int n : {1, 3, 7}) {
      const BoxGeometry box = box_of(dim, {20.0, double(n), dim == 3 ? 12.0 : 0.0});
      const PointCloud c = make_lattice(box, 1.0);
      const BoundaryFacets f = lattice_facets(box, c);
      const ThinSpot spot = thinnest_wall(f, c, box.thickness, 7.5);
      INFO("dim " << dim << ", " << n << " thick");
      REQUIRE(spot.found());
      CHECK(spot.across == Approx(n).epsilon(1e-12));
      CHECK(spot.thickness == Approx(n).epsilon(1e-12));
      CHECK(std::abs(f.normal[spot.facet * dim + 1]) == Approx(1.0));  // measured across y
      CHECK(f.normal[spot.opposite * dim + 1] == Approx(-f.normal[spot.facet * dim + 1]));
    }
  }
  // 8 thick: beyond a reach of 7.5.
  const BoxGeometry box = box_of(2, {20.0, 8.0, 0.0});
  const PointCloud c = make_lattice(box, 1.0);
  CHECK_FALSE(thinnest_wall(lattice_facets(box, c), c, 1.0, 7.5).found());
}

TEST_CASE("a ligament between a hole and a face is found where it is, in a body thick everywhere else", "[geometry]") {
  // 2-D: 40 x 40 with a circle of radius 10 whose top is 3 spacings below the top face.
  BoxGeometry box = box_of(2, {40.0, 40.0, 0.0});
  box.holes.push_back({Hole::Shape::circle, {20.0, 27.0, 0.0}, 10.0, 2});
  PointCloud c = make_lattice(box, 1.0);
  BoundaryFacets f = lattice_facets(box, c);
  ThinSpot spot = thinnest_wall(f, c, box.thickness, 7.5);
  REQUIRE(spot.found());
  CHECK(spot.across == Approx(3.0));
  CHECK(std::abs(f.centroid[spot.facet * 2] - 20.0) < 3.0);  // above the hole (3 across over 6 columns)
  CHECK(f.centroid[spot.facet * 2 + 1] > 36.0);
  // The same hole with 10 spacings of ligament: nothing thin.
  box.holes[0].center[1] = 20.0;
  c = make_lattice(box, 1.0);
  CHECK_FALSE(thinnest_wall(lattice_facets(box, c), c, box.thickness, 7.5).found());
  // 3-D: a cylinder along z leaving 2 spacings beside the right face.
  BoxGeometry box3 = box_of(3, {30.0, 30.0, 10.0});
  box3.holes.push_back({Hole::Shape::cylinder, {20.0, 15.0, 0.0}, 8.0, 2});
  c = make_lattice(box3, 1.0);
  f = lattice_facets(box3, c);
  spot = thinnest_wall(f, c, 1.0, 7.5);
  REQUIRE(spot.found());
  CHECK(spot.across == Approx(2.0));
  CHECK(std::abs(f.normal[spot.facet * 3]) == Approx(1.0));  // across x
}

TEST_CASE("a strip turned off the axes is measured along its own normal", "[geometry]") {
  // A 30 x 4 strip, particles and facets turned by 30 degrees about the origin: the facets'
  // normals are then off the axes, and the opposite facet is found along them.
  const BoxGeometry box = box_of(2, {30.0, 4.0, 0.0});
  PointCloud c = make_lattice(box, 1.0);
  BoundaryFacets f = lattice_facets(box, c);
  const double a = M_PI / 6.0, ca = std::cos(a), sa = std::sin(a);
  const auto turn = [&](std::vector<double>& v) {
    for (std::size_t k = 0; k + 1 < v.size(); k += 2) {
      const double x = v[k], y = v[k + 1];
      v[k] = ca * x - sa * y, v[k + 1] = sa * x + ca * y;
    }
  };
  turn(c.x), turn(f.normal), turn(f.centroid);
  const ThinSpot spot = thinnest_wall(f, c, box.thickness, 7.5);
  REQUIRE(spot.found());
  CHECK(spot.across == Approx(4.0).epsilon(1e-12));
  CHECK(std::abs(f.normal[spot.facet * 2]) == Approx(sa).epsilon(1e-12));  // the strip's turned y
}

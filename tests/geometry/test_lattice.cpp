#include <catch2/catch.hpp>

#include <cmath>

#include "perinom/core/error.hpp"
#include "perinom/geometry/lattice.hpp"

using namespace perinom;

namespace {

BoxGeometry unit_square() {
  BoxGeometry b;
  b.dim = 2;
  b.max = {1.0, 1.0, 0.0};
  return b;
}

}  // namespace

TEST_CASE("a lattice fills its box with round(L / dx) cells per axis", "[geometry]") {
  const PointCloud c = make_lattice(unit_square(), 0.1);
  REQUIRE(c.size() == 100);
  CHECK(c.x[0] == Approx(0.05));
  CHECK(c.volume[0] == Approx(0.01));
}

TEST_CASE("make_lattice refuses a spacing that is not positive and finite", "[geometry]") {
  for (const double dx : {0.0, -0.1, std::nan(""), double(INFINITY)})
    REQUIRE_THROWS_WITH(make_lattice(unit_square(), dx), Catch::Contains("make_lattice: dx = "));
  REQUIRE_THROWS_AS(make_lattice(unit_square(), -0.1), InputError);
}

TEST_CASE("make_lattice refuses an inverted box and a dimension other than 2 or 3", "[geometry]") {
  BoxGeometry inverted = unit_square();
  inverted.min = {1.0, 0.0, 0.0};
  inverted.max = {0.0, 1.0, 0.0};
  REQUIRE_THROWS_WITH(make_lattice(inverted, 0.1), Catch::Contains("min[0] = 1 is not below max[0] = 0"));
  BoxGeometry five = unit_square();
  five.dim = 5;
  REQUIRE_THROWS_WITH(make_lattice(five, 0.1), Catch::Contains("BoxGeometry::dim = 5"));
}

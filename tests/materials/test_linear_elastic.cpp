#include <catch2/catch.hpp>

#include <cmath>

#include "perinom/core/error.hpp"
#include "perinom/materials/linear_elastic.hpp"

using namespace perinom;

namespace {

LinearElastic steel() {
  LinearElastic m;
  m.E = 200e9;
  m.nu = 0.3;
  m.density = 7850;
  m.dim = 3;
  return m;
}

}  // namespace

TEST_CASE("check_material passes a physical material and names the constant that is not", "[materials]") {
  REQUIRE_NOTHROW(check_material(steel()));
  LinearElastic m = steel();
  m.E = 0.0;
  REQUIRE_THROWS_WITH(check_material(m), Catch::Contains("LinearElastic::E = 0"));
  m = steel();
  m.E = -1e9;
  REQUIRE_THROWS_AS(check_material(m), InputError);
  for (const double nu : {0.5, -1.0, 0.7, std::nan("")}) {
    m = steel();
    m.nu = nu;
    REQUIRE_THROWS_WITH(check_material(m), Catch::Contains("LinearElastic::nu"));
  }
  m = steel();
  m.density = 0.0;
  REQUIRE_THROWS_WITH(check_material(m), Catch::Contains("LinearElastic::density = 0"));
  m = steel();
  m.dim = 1;
  REQUIRE_THROWS_WITH(check_material(m), Catch::Contains("LinearElastic::dim = 1"));
}

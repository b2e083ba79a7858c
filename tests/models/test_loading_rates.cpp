// Loading::fix keeps a prescribed velocity whatever the order the constraints come in: the
// first constrained dof too (its rate was lost when a velocity was the first constraint).
#include <catch2/catch.hpp>

#include "perinom/models/loading.hpp"

using namespace perinom;

TEST_CASE("a velocity given to the first constrained dof is kept, and later ones line up", "[loading]") {
  Loading l;
  l.fix(4, 0.0, -1, 2.0);  // the very first constraint: a velocity
  l.fix(5, 0.0);           // a plain fix
  l.fix(7, 0.0, -1, 3.0);
  REQUIRE(l.rate.size() == l.fixed.size());
  CHECK(l.rate[0] == 2.0);
  CHECK(l.rate[1] == 0.0);
  CHECK(l.rate[2] == 3.0);
  CHECK(l.target(1.0, 0, 0.5) == 1.0);  // v t
  // Fixed first, a velocity later: the earlier dofs get rate 0.
  Loading m;
  m.fix(1, 0.0);
  m.fix(2, 0.0, -1, 1.5);
  REQUIRE(m.rate.size() == 2);
  CHECK(m.rate[0] == 0.0);
  CHECK(m.rate[1] == 1.5);
}

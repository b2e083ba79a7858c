// BondBreaking::state() and restore() (checkpoints of cracking runs): a fresh model restored
// from a state breaks the same bonds into the same operator bits, and gives back the same
// state (softening bonds with their committed openings); states that do not fit are refused.
// The whole run resumed is tests/cli/test_restart.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "perinom/fracture/bond_breaking.hpp"
#include "perinom/models/cohesive_bonds.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/scene.hpp"

using namespace perinom;

namespace {

/// A pull in y with a bump near the notch tip: bonds there stretch beyond s_c.
std::vector<double> pull(const PointCloud& c, double amount) {
  std::vector<double> u(c.size() * 2, 0.0);
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double x = c.x[2 * i], y = c.x[2 * i + 1];
    u[2 * i + 1] = amount * y * (1.0 + 40.0 * std::exp(-((x - 5e-4) * (x - 5e-4) + (y - 5e-4) * (y - 5e-4)) / 1e-8));
  }
  return u;
}

}  // namespace

TEST_CASE("a bond-breaking state restored into a fresh model gives the same operators and state", "[fracture][checkpoint]") {
  const Scene scene = read_scene(std::string(PERINOM_SOURCE_DIR) + "/examples/sent.yaml");
  Problem a = build_problem(scene), b = build_problem(scene);
  BondBreaking breaking(a.as<CorrespondenceModel>(), a.cloud, DamageCriterion::stretch, 0.01);
  breaking.stable_time_step();  // from here on apply() keeps the row sums, row by row
  std::size_t groups = 0;
  for (const double amount : {0.004, 0.008, 0.012}) {
    const std::vector<double> u = pull(a.cloud, amount);
    if (breaking.find(u.data()) > 0) breaking.apply(), ++groups;
  }
  REQUIRE(groups >= 2);
  REQUIRE(breaking.broken() > 10);
  const std::vector<double> state = breaking.state();

  BondBreaking again(b.as<CorrespondenceModel>(), b.cloud, DamageCriterion::stretch, 0.01);
  again.restore(state);
  CHECK(again.broken() == breaking.broken());
  CHECK(again.detached() == breaking.detached());
  CHECK(again.state() == state);
  const std::vector<double> u = pull(a.cloud, 0.003);
  std::vector<double> fa(u.size()), fb(u.size());
  a.physics().internal_force(u.data(), fa.data());
  b.physics().internal_force(u.data(), fb.data());
  CHECK(fa == fb);  // bit for bit
  CHECK(again.stable_time_step() == breaking.stable_time_step());
  // The row sums restore keeps are the run's, bit for bit; and they are the model's: a sum
  // over every row of the changed model agrees to rounding (its order differs).
  CHECK(again.row_sums() == breaking.row_sums());
  const std::vector<double> anew = b.as<CorrespondenceModel>().stiffness_row_sums();
  REQUIRE(anew.size() == breaking.row_sums().size());
  double worst = 0.0, largest = 0.0;
  for (std::size_t k = 0; k < anew.size(); ++k)
    worst = std::max(worst, std::abs(anew[k] - breaking.row_sums()[k])), largest = std::max(largest, anew[k]);
  CHECK(worst <= 1e-12 * largest);


  SECTION("states that do not fit are refused") {
    Problem c = build_problem(scene);
    BondBreaking fresh(c.as<CorrespondenceModel>(), c.cloud, DamageCriterion::stretch, 0.01);
    std::vector<double> cut(state.begin(), state.end() - 1);
    CHECK_THROWS_AS(fresh.restore(cut), std::invalid_argument);
    std::vector<double> far = state;
    far.back() = double(c.cloud.size());
    CHECK_THROWS_AS(fresh.restore(far), std::invalid_argument);
    std::vector<double> armed = state;
    armed[3] = 1.0;  // the instability criterion's, restored into a stretch criterion
    CHECK_THROWS_AS(fresh.restore(armed), std::invalid_argument);
    CHECK_THROWS_AS(again.restore(state), std::invalid_argument);  // bonds broken already
  }
}

TEST_CASE("with softening bonds the state holds their committed openings, and restores them", "[fracture][checkpoint][cohesive]") {
  const Scene scene = read_scene(std::string(PERINOM_SOURCE_DIR) + "/examples/sent.yaml");
  Problem a = build_problem(scene), b = build_problem(scene), plain = build_problem(scene);
  const CohesiveLaw law{1.0e9, 2700.0, a.as<CorrespondenceModel>().material().E};
  a.as<CorrespondenceModel>().soften_broken_bonds(law);
  b.as<CorrespondenceModel>().soften_broken_bonds(law);
  BondBreaking breaking(a.as<CorrespondenceModel>(), a.cloud, DamageCriterion::stretch, 0.01);
  BondBreaking unsoftened(plain.as<CorrespondenceModel>(), plain.cloud, DamageCriterion::stretch, 0.01);
  for (const double amount : {0.004, 0.008, 0.012, 0.006}) {  // find commits the openings first
    const std::vector<double> u = pull(a.cloud, amount);
    if (breaking.find(u.data()) > 0) breaking.apply();
    if (unsoftened.find(u.data()) > 0) unsoftened.apply();
  }
  const CohesiveBonds& soft = *a.as<CorrespondenceModel>().cohesive();
  REQUIRE(soft.size() == breaking.broken());
  const std::vector<double> kappa = soft.kappas();
  REQUIRE(std::count_if(kappa.begin(), kappa.end(), [](double k) { return k > 0.0; }) > 0);
  const std::vector<double> state = breaking.state();
  REQUIRE(state.size() == unsoftened.state().size() + soft.size());  // one opening per bond

  BondBreaking again(b.as<CorrespondenceModel>(), b.cloud, DamageCriterion::stretch, 0.01);
  again.restore(state);
  CHECK(b.as<CorrespondenceModel>().cohesive()->kappas() == kappa);
  CHECK(again.state() == state);
  const std::vector<double> u = pull(a.cloud, 0.005);
  std::vector<double> fa(u.size()), fb(u.size());
  a.physics().internal_force(u.data(), fa.data());
  b.physics().internal_force(u.data(), fb.data());
  CHECK(fa == fb);  // bit for bit, the softening bonds' secant included

  SECTION("a state without the openings, or with them into a model without softening bonds, is refused") {
    Problem c = build_problem(scene), e = build_problem(scene);
    c.as<CorrespondenceModel>().soften_broken_bonds(law);
    BondBreaking fresh(c.as<CorrespondenceModel>(), c.cloud, DamageCriterion::stretch, 0.01);
    CHECK_THROWS_AS(fresh.restore(unsoftened.state()), std::invalid_argument);
    CHECK(c.as<CorrespondenceModel>().cohesive()->size() == 0);  // refused before any break
    BondBreaking without(e.as<CorrespondenceModel>(), e.cloud, DamageCriterion::stretch, 0.01);
    CHECK_THROWS_AS(without.restore(state), std::invalid_argument);
  }
}

// With softening bonds (damage.fracture_energy) the stress criterion hands a bond to its law
// only once it is opened to the law's peak, or once both its particles have such a bond: a
// crack opening breaks the bonds across it and the bonds among the particles it cracks, but
// not the bonds from them into the body, which the plain criterion breaks too (their mean
// stress is over f_t); a uniform field over f_t breaks what the plain criterion breaks.
#include <catch2/catch.hpp>

#include <cmath>

#include "perinom/fracture/bond_breaking.hpp"
#include "perinom/models/cohesive_bonds.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/scene.hpp"

using namespace perinom;

namespace {

const double f_t = 1.0e6, crack = 0.05;  // Pa; the opening's plane x = crack (between two columns)

/// The brittle bar (50 x 10 particles, dx = 2 mm, horizon 6.03 mm), with softening bonds or not.
struct Bar {
  Problem p;
  explicit Bar(bool softening) : p(build_problem(read_scene(std::string(PERINOM_SOURCE_DIR) + "/examples/brittle_bar.yaml"))) {
    CorrespondenceModel& m = p.as<CorrespondenceModel>();
    if (softening) m.soften_broken_bonds(CohesiveLaw{f_t, 50.0, m.material().E});
  }
  std::vector<BondPair> due(const std::vector<double>& u) {
    BondBreaking b(p.as<CorrespondenceModel>(), p.cloud, DamageCriterion::stress, f_t);
    b.find(u.data());
    return b.due();
  }
};

bool crosses(const PointCloud& c, const BondPair& b) {
  return (c.x[2 * std::size_t(b.first)] - crack) * (c.x[2 * std::size_t(b.second)] - crack) < 0.0;
}

}  // namespace

TEST_CASE("with softening bonds a crack's opening breaks the bonds across it, not the bonds beside it",
          "[fracture][cohesive]") {
  Bar plain(false), soft(true);
  const PointCloud& c = soft.p.cloud;
  // The right part moved rigidly by 10 um: the particles within a horizon of the plane see a
  // gradient far over f_t / E, the others none. Every bond across opens far past eta_e.
  std::vector<double> u(c.size() * 2, 0.0);
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c.x[2 * i] > crack) u[2 * i] = 1.0e-5;
  const std::vector<BondPair> all = plain.due(u), gated = soft.due(u);
  const double horizon = 3.015 * 0.002;
  std::size_t across = 0, into_body = 0;
  for (const BondPair& b : all) {
    across += crosses(c, b);
    const double far = std::max(std::abs(c.x[2 * std::size_t(b.first)] - crack), std::abs(c.x[2 * std::size_t(b.second)] - crack));
    into_body += far > horizon;
  }
  REQUIRE(across > 0);
  REQUIRE(into_body > 0);  // the plain criterion breaks bonds reaching past the cracked particles
  std::size_t gated_across = 0;
  for (const BondPair& b : gated) {
    gated_across += crosses(c, b);
    // Every end of a bond the gate lets through is a particle the opening cracks.
    CHECK(std::abs(c.x[2 * std::size_t(b.first)] - crack) < horizon);
    CHECK(std::abs(c.x[2 * std::size_t(b.second)] - crack) < horizon);
  }
  CHECK(gated_across == across);  // every bond across that the plain criterion breaks
  CHECK(gated.size() < all.size());
}

TEST_CASE("with softening bonds a uniform pull over f_t breaks what the plain stress criterion breaks",
          "[fracture][cohesive]") {
  Bar plain(false), soft(true);
  const PointCloud& c = soft.p.cloud;
  const double E = soft.p.as<CorrespondenceModel>().material().E, nu = soft.p.as<CorrespondenceModel>().material().nu;
  // Uniaxial plane stress at 1.05 f_t: the bonds along x are stretched 1.05 f_t / E, past eta_e
  // = |xi| f_t / E, so every particle has one at its peak; the inclined ones are not.
  const double strain = 1.05 * f_t / E;
  std::vector<double> u(c.size() * 2);
  for (std::size_t i = 0; i < c.size(); ++i) u[2 * i] = strain * c.x[2 * i], u[2 * i + 1] = -nu * strain * c.x[2 * i + 1];
  const std::vector<BondPair> all = plain.due(u), gated = soft.due(u);
  REQUIRE(all.size() > 1000);
  CHECK(gated == all);
  // At 0.95 f_t nothing breaks either way.
  for (double& x : u) x *= 0.95 / 1.05;
  CHECK(plain.due(u).empty());
  CHECK(soft.due(u).empty());
}

TEST_CASE("a softening bond is at its law's peak from eta_e = |xi| f_t / E on", "[models][cohesive]") {
  const std::vector<double> x{0.0, 0.0, 0.003, 0.004}, volume{1e-6, 1e-6};  // |xi| = 5 mm, e = (0.6, 0.8)
  Families f;
  f.offsets = {0, 1, 2};
  f.neighbors = {1, 0};
  const BondGraph graph(f);
  const CohesiveLaw law{f_t, 50.0, 30.0e9};
  const CohesiveBonds bonds(2, x, volume, graph, law);
  const double eta_e = 0.005 * f_t / 30.0e9;
  for (const double s : {0.999, 1.001}) {
    const std::vector<double> u{0.0, 0.0, 0.6 * s * eta_e, 0.8 * s * eta_e};  // opened by s eta_e along e
    CHECK(bonds.at_peak(0, 1, u.data()) == (s > 1.0));
    CHECK(bonds.at_peak(1, 0, u.data()) == (s > 1.0));
  }
  const std::vector<double> shear{0.0, 0.0, -0.8 * 2.0 * eta_e, 0.6 * 2.0 * eta_e};  // across e: not opened
  CHECK_FALSE(bonds.at_peak(0, 1, shear.data()));
}

// model.stabilization_scale: secant. The elastic stabilization resists a plastic mechanism's
// flow and never yields (Prandtl's footing rose without end); with secant each family's block
// of S is scaled by its particle's committed secant shear stiffness over the elastic one.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "../support/clouds.hpp"
#include "perinom/core/error.hpp"
#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/models/plastic_points.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

namespace {

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

// von Mises in Drucker-Prager's form: phi = 0, no hardening; sqrt(J2) at yield k = 2 c / sqrt(3).
DruckerPrager von_mises() {
  DruckerPrager dp;
  dp.E = 1e8, dp.nu = 0.3, dp.friction_angle = 0.0, dp.cohesion = 1e5;
  return dp;
}

// The facets of test::lattice(2, n, ...)'s box [0, n]^2.
BoundaryFacets facets_of(const PointCloud& c, int n) {
  BoxGeometry box;
  box.dim = 2, box.max[0] = box.max[1] = n;
  return lattice_facets(box, c);
}

LinearElastic elastic_of(const DruckerPrager& dp) {
  LinearElastic m;
  m.E = dp.E, m.nu = dp.nu, m.density = 2000.0, m.dim = 2, m.plane = PlaneCondition::strain;
  return m;
}

}  // namespace

TEST_CASE("the secant ratio is 1 while elastic and k / (G gamma) in simple shear past yield", "[models]") {
  const DruckerPrager dp = von_mises();
  const double G = dp.shear(), k = 2.0 * dp.cohesion / std::sqrt(3.0), gamma_y = k / G;
  PlasticPoints points(dp, 2, 3);
  points.set_mode(PlasticMode::return_map);
  CHECK(points.secant_ratios() == std::vector<double>(3, 1.0));  // no strain
  // Simple shear u_x = gamma y (grad u = [[0, gamma], [0, 0]]): half, two and five times the
  // yield strain, each particle from the virgin state in one increment.
  const double gammas[3] = {0.5 * gamma_y, 2.0 * gamma_y, 5.0 * gamma_y};
  double P[4];
  for (std::size_t i = 0; i < 3; ++i) {
    const double H[4] = {0.0, gammas[i], 0.0, 0.0};
    points.stress(i, H, P);
  }
  CHECK(points.secant_ratios() == std::vector<double>(3, 1.0));  // trial states do not count
  points.commit();
  const std::vector<double> r = points.secant_ratios();
  CHECK(r[0] == Approx(1.0).epsilon(1e-12));
  CHECK(r[1] == Approx(k / (G * gammas[1])).epsilon(1e-9));  // 0.5
  CHECK(r[2] == Approx(k / (G * gammas[2])).epsilon(1e-9));  // 0.2
}

TEST_CASE("a secant stabilization changes the force only where the committed state has yielded, as the next step "
          "begins, and follows the history",
          "[models]") {
  const PointCloud c = test::lattice(2, 8, 0.25);
  const Families f = radius_families(c, 3.015);
  const DruckerPrager dp = von_mises();
  for (const Formulation form : {Formulation::classical, Formulation::consistent}) {
    INFO((form == Formulation::classical ? "classical" : "consistent"));
    CorrespondenceOptions opt;
    opt.formulation = form, opt.operator_order = 2, opt.plasticity = dp;
    const BoundaryFacets facets = form == Formulation::consistent ? facets_of(c, 8) : BoundaryFacets{};
    CorrespondenceModel plain(c, f, elastic_of(dp), opt, {}, facets);
    opt.secant_stabilization = true;
    CorrespondenceModel secant(c, f, elastic_of(dp), opt, {}, facets);
    REQUIRE(secant.stabilization() != nullptr);
    CHECK(secant.stabilization()->level() == AssemblyLevel::matrix_free);  // (auto chose it)
    // A shear with a bump: non-affine, so S acts; past yield in the middle of the block.
    std::vector<double> u(c.size() * 2), fp(u.size()), fs(u.size());
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double x = c.x[i * 2], y = c.x[i * 2 + 1];
      u[i * 2] = 0.005 * y * std::exp(-0.25 * ((x - 4.0) * (x - 4.0) + (y - 4.0) * (y - 4.0)));
    }
    for (ModelHistory* h : {plain.history(), secant.history()}) h->set_history_mode(HistoryMode::return_map);
    // Before any commit every factor is 1: the same force (to rounding: the plain model stores
    // S assembled, the secant one applies it matrix-free).
    plain.internal_force(u.data(), fp.data());
    secant.internal_force(u.data(), fs.data());
    CHECK(max_difference(fp, fs) <= 1e-11 * test::max_abs(fp));
    plain.commit(u.data()), secant.commit(u.data());
    // The commit keeps the force the state was balanced with (its reactions are the balance's).
    std::vector<double> after(u.size());
    secant.internal_force(u.data(), after.data());
    CHECK(after == fs);
    const std::vector<double> xi = secant.history_variable();
    const std::size_t yielded = static_cast<std::size_t>(std::count_if(xi.begin(), xi.end(), [](double v) { return v > 0.0; }));
    INFO(yielded << " of " << c.size() << " particles yielded");
    REQUIRE(yielded > 0);
    REQUIRE(yielded < c.size());
    // As the next step begins, a further non-affine increment meets less stabilization.
    plain.begin_step(), secant.begin_step();
    std::vector<double> v(u);
    for (std::size_t i = 0; i < c.size(); ++i) v[i * 2 + 1] += 1e-4 * std::sin(2.0 * c.x[i * 2]) * std::cos(1.5 * c.x[i * 2 + 1]);
    plain.internal_force(v.data(), fp.data());
    secant.internal_force(v.data(), fs.data());
    CHECK(max_difference(fp, fs) > 1e-3 * test::max_abs(fp));
    // Saved, reset (factors back to 1 as a step begins), restored (factors back): the force
    // follows the history.
    const HistoryState saved = secant.save_history();
    std::vector<double> before(fs), virgin(u.size()), fresh(u.size());
    secant.reset_history(), plain.reset_history();
    secant.begin_step(), plain.begin_step();
    secant.internal_force(v.data(), virgin.data());
    plain.internal_force(v.data(), fresh.data());
    CHECK(max_difference(virgin, fresh) <= 1e-11 * test::max_abs(fresh));
    secant.restore_history(saved);
    secant.begin_step();
    secant.internal_force(v.data(), fs.data());
    CHECK(fs == before);
  }
}

TEST_CASE("a secant stabilization is refused where it cannot act", "[models]") {
  const PointCloud c = test::lattice(2, 6, 0.25);
  const Families f = radius_families(c, 3.015);
  const DruckerPrager dp = von_mises();
  CorrespondenceOptions opt;
  opt.secant_stabilization = true;
  CHECK_THROWS_AS(CorrespondenceModel(c, f, elastic_of(dp), opt), std::invalid_argument);  // no plastic law
  opt.plasticity = dp;
  opt.stabilization_storage = StabilizationStorage::assembled;
  CHECK_THROWS_AS(CorrespondenceModel(c, f, elastic_of(dp), opt), InputError);  // a stored S sums the blocks
  opt.stabilization_storage = StabilizationStorage::automatic;
  opt.formulation = Formulation::consistent, opt.operator_order = 1;
  CHECK_THROWS_AS(CorrespondenceModel(c, f, elastic_of(dp), opt, {}, facets_of(c, 6)), InputError);
}

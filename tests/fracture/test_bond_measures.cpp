// What the fracture criteria measure: hourglass strains vanish on affine fields, stretches
// and bond stresses are the bond's own, damage weighs the broken neighbours' volumes, and the
// criteria break strictly above their thresholds, never a dead bond.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "../../lib/fracture/bond_selection.hpp"
#include "../support/clouds.hpp"
#include "perinom/fracture/bond_measures.hpp"
#include "perinom/fracture/criteria.hpp"
#include "perinom/materials/measures.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/operators/bond_weights.hpp"
#include "perinom/operators/hourglass_energy.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
#include "perinom/operators/stabilization.hpp"

using namespace perinom;

TEST_CASE("the hourglass strain of an affine field is zero to rounding, and not of a quadratic one", "[fracture]") {
  for (const int d : {2, 3}) {
    const PointCloud c = test::lattice(d, d == 2 ? 10 : 6, 0.3);
    const Families f = radius_families(c, 2.515);
    auto graph = std::make_shared<BondGraph>(f);
    const NonlocalOperator G(c, graph, bond_weights(c, f, Influence::inverse_square));
    // u = A x + b with a full A (stretch, shear and rotation).
    const double A[9] = {1e-3, 2e-3, -1e-3, 4e-4, -2e-3, 3e-3, 5e-4, 1e-3, 2e-3};
    std::vector<double> u(c.size() * d), H(c.size() * d * d), s;
    for (std::size_t i = 0; i < c.size(); ++i)
      for (int a = 0; a < d; ++a) {
        u[i * d + a] = 1e-4 * (a + 1);
        for (int b = 0; b < d; ++b) u[i * d + a] += A[a * 3 + b] * c.x[i * d + b];
      }
    G.apply(u.data(), d, H.data());
    hourglass_strains(c, *graph, u.data(), H.data(), s);
    INFO("dim " << d);
    REQUIRE(s.size() == graph->bonds());
    CHECK(test::max_abs(s) <= 1e-11 * 3e-3);
    // A quadratic field: the gradient misses the curvature, bonds see it.
    for (std::size_t i = 0; i < c.size(); ++i) u[i * d] = 1e-3 * c.x[i * d] * c.x[i * d];
    G.apply(u.data(), d, H.data());
    hourglass_strains(c, *graph, u.data(), H.data(), s);
    CHECK(test::max_abs(s) > 1e-4);
    // A dead bond measures 0.
    graph->break_bond(0, graph->col(graph->begin(0)));
    hourglass_strains(c, *graph, u.data(), H.data(), s);
    CHECK(s[graph->begin(0)] == 0.0);
  }
}

TEST_CASE("bond stretch, bond stress, principal stress and damage are the bond's and the particle's own",
          "[fracture]") {
  const PointCloud c = test::lattice(2, 6, 0.0);
  const Families f = radius_families(c, 1.515);
  BondGraph g(f);
  // A uniform extension eps along x: a bond along x stretches by eps, one along y not at all.
  const double eps = 1e-3;
  std::vector<double> u(c.size() * 2, 0.0), s, t;
  for (std::size_t i = 0; i < c.size(); ++i) u[i * 2] = eps * c.x[i * 2];
  bond_stretches(c, g, u.data(), s);
  for (std::size_t i = 0; i < g.rows(); ++i)
    for (Offset k = g.begin(i); k < g.end(i); ++k) {
      const std::size_t j = g.col(k);
      const double dx = c.x[j * 2] - c.x[i * 2], dy = c.x[j * 2 + 1] - c.x[i * 2 + 1];
      if (std::abs(dy) < 1e-12) CHECK(s[k] == Approx(eps).epsilon(1e-9));
      if (std::abs(dx) < 1e-12) CHECK(std::abs(s[k]) <= 1e-15);
    }
  // Bond stress: the mean of the two particles' sigma1.
  std::vector<double> sigma1(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) sigma1[i] = double(i);
  bond_stresses(g, sigma1, t);
  for (std::size_t i = 0; i < g.rows(); ++i)
    for (Offset k = g.begin(i); k < g.end(i); ++k) CHECK(t[k] == 0.5 * (double(i) + double(g.col(k))));
  // sigma1 of diag(1, 5, -2), turned by 30 degrees about z: 5.
  const double cs = std::cos(M_PI / 6), sn = std::sin(M_PI / 6);
  const double a = 1.0, b = 5.0;
  const double sig[9] = {cs * cs * a + sn * sn * b, cs * sn * (b - a), 0.0, cs * sn * (b - a), sn * sn * a + cs * cs * b,
                         0.0, 0.0, 0.0, -2.0};
  CHECK(max_principal_stress(sig) == Approx(5.0).epsilon(1e-14));
  const double hydro[9] = {3, 0, 0, 0, 3, 0, 0, 0, 3};
  CHECK(max_principal_stress(hydro) == 3.0);
  // Damage: a particle whose bonds all break has d = 1; its neighbours lose one of their
  // neighbours' volumes each. Volumes differ here, so the weighting shows.
  std::vector<double> volume(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) volume[i] = 1.0 + 0.1 * double(i);
  const std::size_t p = 14;
  for (Offset k = g.begin(p); k < g.end(p); ++k) g.break_bond(static_cast<ParticleId>(p), g.col(k));
  const std::vector<double> dmg = damage(g, volume);
  CHECK(dmg[p] == 1.0);
  for (Offset k = g.begin(p); k < g.end(p); ++k) {
    const std::size_t j = g.col(k);
    double all = 0.0;
    for (Offset q = g.begin(j); q < g.end(j); ++q) all += volume[g.col(q)];
    CHECK(dmg[j] == Approx(volume[p] / all).epsilon(1e-14));
  }
  CHECK(dmg[0] == 0.0);
}

TEST_CASE("each break event stamps its bonds, and a particle reports the first event it lost a bond in",
          "[fracture]") {
  const PointCloud c = test::lattice(2, 6, 0.0);
  BondGraph g(radius_families(c, 1.515));
  CHECK(g.events() == 0);
  CHECK(g.memory_bytes() == BondGraph(radius_families(c, 1.515)).memory_bytes());  // intact: no stamps kept
  // Event 1 breaks (14, 15); event 2 breaks (14, 20) and (7, 8); (7, 8) again in event 3 is
  // already dead and keeps its stamp.
  g.begin_event();
  REQUIRE(g.break_bond(14, 15));
  g.begin_event();
  REQUIRE(g.break_bond(14, 20));
  REQUIRE(g.break_bond(8, 7));
  g.begin_event();
  CHECK_FALSE(g.break_bond(7, 8));
  CHECK(g.events() == 3);
  CHECK(g.event(g.find(14, 15)) == 1);
  CHECK(g.event(g.find(15, 14)) == 1);
  CHECK(g.event(g.find(20, 14)) == 2);
  CHECK(g.event(g.find(7, 8)) == 2);
  CHECK(g.event(g.find(14, 13)) == 0);  // alive
  const std::vector<double> first = first_break_event(g);
  CHECK(first[14] == 1.0);  // lost (14, 15) first, then (14, 20)
  CHECK(first[15] == 1.0);
  CHECK(first[20] == 2.0);
  CHECK(first[7] == 2.0);
  CHECK(first[8] == 2.0);
  CHECK(first[0] == 0.0);
  CHECK(std::count(first.begin(), first.end(), 0.0) == std::ptrdiff_t(c.size()) - 5);
  // Settled (the cuts are the body as built): no particle reports them, and the next event
  // is 1 again; a particle cut at build time reports the first event that breaks more of it.
  g.settle_events();
  CHECK(g.events() == 0);
  CHECK(g.event(g.find(14, 15)) == 0);
  CHECK_FALSE(g.alive(g.find(14, 15)));
  const std::vector<double> none = first_break_event(g);
  CHECK(std::count(none.begin(), none.end(), 0.0) == std::ptrdiff_t(c.size()));
  g.begin_event();
  REQUIRE(g.break_bond(14, 13));
  const std::vector<double> later = first_break_event(g);
  CHECK(later[14] == 1.0);
  CHECK(later[13] == 1.0);
  CHECK(later[15] == 0.0);
}

TEST_CASE("criteria break strictly above their thresholds, and the instability criterion arms once", "[fracture]") {
  const PointCloud c = test::lattice(2, 5, 0.0);
  BondGraph g(radius_families(c, 1.515));
  const std::size_t nb = g.bonds();
  std::vector<double> stretch(nb, 0.001), hg(nb, 0.0);
  for (std::size_t k = 0; k < nb; ++k) hg[k] = 1e-4 * double(k % 7);
  // A bond exactly at the threshold holds; one above breaks.
  std::vector<double> m(nb, 1.0);
  m[3] = 2.0;
  const auto above = bonds_above(g, m, 1.0);
  REQUIRE(above.size() == 1);
  InstabilityCriterion crit(0.01);
  CHECK(crit.select(g, stretch, hg).empty());
  CHECK_FALSE(crit.armed());
  stretch[5] = 0.01;  // the largest stretch reaches s_max: armed at the largest hourglass strain
  CHECK(crit.select(g, stretch, hg).empty());
  REQUIRE(crit.armed());
  CHECK(crit.threshold() == Approx(6e-4));
  hg[2] = 7e-4;  // now above; bond 9 exactly at it holds
  hg[9] = 6e-4;
  const auto breaks = crit.select(g, stretch, hg);
  REQUIRE(breaks.size() == 1);
  CHECK(g.find(breaks[0].first, breaks[0].second) == 2);
  // Broken, it is never selected again, however large its measure.
  g.break_bond(breaks[0].first, breaks[0].second);
  hg[2] = 1.0;
  for (const auto& [i, j] : crit.select(g, stretch, hg)) CHECK(g.alive(g.find(i, j)));
  CHECK_THROWS_AS(InstabilityCriterion(0.0), std::invalid_argument);
}

TEST_CASE("the one-pass bond selection equals the per-bond arrays and does not depend on the thread count", "[fracture]") {
  // What BondBreaking runs each step (lib/fracture/bond_selection.hpp), comparing squares
  // (no root per bond), against the array form of the stretches and hourglass strains.
  const PointCloud c = test::lattice(2, 60, 0.3);
  BondGraph g(radius_families(c, 3.015));
  g.break_bond(0, g.col(g.begin(0)));  // a dead bond is never selected
  const auto u = test::random_field(c.size() * 2, 1e-2, 5);
  std::vector<double> H(c.size() * 4);
  for (std::size_t k = 0; k < H.size(); ++k) H[k] = 1e-2 * std::cos(0.37 * k);
  const BondStretch stretch{2, c.x.data(), u.data()};
  const HourglassStrain hourglass{2, c.x.data(), u.data(), H.data()};
  std::vector<double> s, h;
  bond_stretches(c, g, u.data(), s);
  hourglass_strains(c, g, u.data(), H.data(), h);
  const double s_top = *std::max_element(s.begin(), s.end()), h_top = *std::max_element(h.begin(), h.end());
  const double s_c = 0.5 * s_top, t = 0.5 * h_top;
  const auto by_stretch = bonds_above(g, s, s_c), by_hourglass = bonds_above(g, h, t);
  REQUIRE(by_stretch.size() > 10);
  REQUIRE(by_hourglass.size() > 10);
  const int before = omp_get_max_threads();
  for (const int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    CHECK(detail::live_bonds_where(g, [&](std::size_t i, std::size_t j) { return stretch.exceeds(i, j, s_c); }) ==
          by_stretch);
    CHECK(detail::live_bonds_where(g, [&](std::size_t i, std::size_t j) { return hourglass.exceeds(i, j, t); }) ==
          by_hourglass);
    CHECK(detail::live_maximum(g, stretch) == s_top);
    const double r = detail::live_maximum(g, [&](std::size_t i, std::size_t j) { return stretch.squared_ratio(i, j); });
    CHECK(std::sqrt(r) - 1.0 == Approx(s_top).epsilon(1e-12));
    const double q = detail::live_maximum(g, [&](std::size_t i, std::size_t j) { return hourglass.squared(i, j); });
    CHECK(std::sqrt(q) == Approx(h_top).epsilon(1e-14));
  }
  omp_set_num_threads(before);
}

TEST_CASE("the hourglass energy density sums to the stabilization's energy, with broken bonds", "[fracture]") {
  for (const int d : {2, 3}) {
    INFO("dim " << d);
    const PointCloud c = test::lattice(d, d == 2 ? 12 : 6, 0.3);
    const Families f = radius_families(c, 2.515);
    auto graph = std::make_shared<BondGraph>(f);
    NonlocalOperator G(c, graph, bond_weights(c, f, Influence::inverse_square));
    // Break every fifth bond of the first half of the rows, then refresh those rows.
    std::vector<BondPair> cut;
    for (std::size_t i = 0; i < c.size() / 2; ++i)
      for (Offset k = f.begin(i); k < f.end(i); k += 5) cut.emplace_back(static_cast<ParticleId>(i), f.neighbors[k]);
    const std::vector<ParticleId> rows = graph->rows_touched(cut);
    for (const auto& [i, j] : cut) graph->break_bond(i, j);
    G.refresh_rows(rows);
    const double modulus = 0.5 * 2.0 * 80e9;
    const Stabilization S(c, G, modulus);
    const std::vector<double> u = test::random_field(c.size() * d, 1e-4);
    std::vector<double> H(c.size() * d * d);
    G.apply(u.data(), d, H.data());
    const std::vector<double> psi = hourglass_energy_density(G, u.data(), modulus);
    double sum = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      CHECK(psi[i] >= 0.0);
      sum += c.volume[i] * psi[i];
    }
    const double W = S.energy(u.data(), d, H.data(), nullptr);
    REQUIRE(W > 0.0);
    CHECK(sum == Approx(W).epsilon(1e-12));
    // An affine field stores none.
    std::vector<double> v(c.size() * d);
    for (std::size_t i = 0; i < c.size(); ++i)
      for (int a = 0; a < d; ++a) v[i * d + a] = 1e-3 * c.x[i * d + (a + 1) % d] - 2e-3 * c.x[i * d + a];
    const std::vector<double> zero = hourglass_energy_density(G, v.data(), modulus);
    CHECK(*std::max_element(zero.begin(), zero.end()) <= 1e-20 * modulus);
  }
}

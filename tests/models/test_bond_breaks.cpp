// Bonds broken through the model (CorrespondenceModel::break_bonds): force, energy, tangent
// rows and the ADR stiffness bound equal those of a model built without the bonds, at every
// stabilization storage; a particle that loses its family is detached and carries nothing.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "../support/refresh.hpp"
#include "../support/clouds.hpp"
#include "perinom/geometry/surface.hpp"
#include "perinom/materials/material_point.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

namespace {

LinearElastic material(int dim) { return test::elastic_material(dim); }

double relative(const std::vector<double>& a, const std::vector<double>& b) { return test::relative_difference(a, b); }

/// The tangent rows as (row, column) -> block.
test::Rows rows_of(const CorrespondenceModel& m) {
  test::Rows rows;
  const int d = m.dofs_per_particle();
  m.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
#pragma omp critical
    for (std::size_t q = 0; q < cols.size(); ++q)
      rows[{i, cols[q]}] = std::vector<double>(blocks.begin() + q * d * d, blocks.begin() + (q + 1) * d * d);
  });
  return rows;
}

using test::rows_difference;

BoxGeometry box(int d, int side) {
  BoxGeometry b;
  b.dim = d;
  for (int a = 0; a < d; ++a) b.max[a] = side;
  return b;
}

constexpr double tolerance = 1e-13;

}  // namespace

namespace {

/// One case of the refresh tests: a small lattice, radius or nearest-neighbour families.
struct Case {
  int d;
  bool knn;
  PointCloud cloud;
  Families families;
  Surface surface;
  CorrespondenceOptions options;
};

/// Runs body(case) over dimension, families, formulation, operator order and stabilization
/// storage: fused needs symmetric families (radius), and order 2 refreshes at the matrix-free
/// level only (the assembled one drops its fit).
template <class Body>
void for_each_case(Body&& body) {
  using Storage = StabilizationStorage;
  for (const int d : {2, 3})
    for (const bool knn : {false, true})
      for (const Formulation form : {Formulation::classical, Formulation::improved})
        for (const int order : {1, 2})
          for (const Storage storage : {Storage::fused, Storage::assembled, Storage::matrix_free}) {
            if (knn && storage == Storage::fused) continue;
            if (order == 2 && storage != Storage::matrix_free) continue;
            const int side = d == 2 ? 10 : 6;
            Case c{d, knn, test::lattice(d, side, 0.3), {}, {}, {Influence::inverse_square, 0.5, form}};
            c.families = knn ? knn_families(c.cloud, d == 2 ? 16 : 36) : radius_families(c.cloud, 2.515);
            c.surface = find_surface(box(d, side), c.cloud, 2.0);
            c.options.stabilization_storage = storage;
            c.options.operator_order = order;
            INFO("dim " << d << (knn ? " knn" : " radius") << " order " << order << " formulation " << int(form)
                        << " storage " << int(storage));
            body(c);
          }
}

}  // namespace

TEST_CASE("a model whose bonds break equals a model built without them", "[models][refresh]") {
  for_each_case([](const Case& c) {
    const Families& f = c.families;
    CorrespondenceModel model(c.cloud, f, material(c.d), c.options, c.surface);
    const std::vector<test::Bond> breaks = test::random_bonds(f, c.cloud.size() / 8, 17);
    const BondBreaks report = model.break_bonds(breaks);
    INFO(report.broken << " bonds broken, " << report.rows.size() << " rows");
    REQUIRE(report.broken == breaks.size());
    REQUIRE(report.detached.empty());
    // Breaking again changes nothing.
    CHECK(model.break_bonds(breaks).broken == 0);

    const Families f2 = test::without(f, std::set<test::Bond>(breaks.begin(), breaks.end()));
    CorrespondenceModel built(c.cloud, f2, material(c.d), c.options, c.surface);
    const auto u = test::random_field(model.dofs(), 1e-4, 21);
    std::vector<double> fa(u.size()), fb(u.size());
    model.internal_force(u.data(), fa.data());
    built.internal_force(u.data(), fb.data());
    CHECK(relative(fa, fb) <= tolerance);
    CHECK(std::abs(model.energy(u.data()) - built.energy(u.data())) <= tolerance * built.energy(u.data()));
    CHECK(rows_difference(rows_of(model), rows_of(built)) <= tolerance);
    CHECK(relative(model.stiffness_row_sums(), built.stiffness_row_sums()) <= tolerance);
  });
}

TEST_CASE("breaking at a state updates its force and energy as if both were taken anew", "[models][refresh]") {
  // break_bonds(bonds, u, f): f, the force at u, becomes the changed model's force there, and
  // `released` the energy difference. The classical formulation of order 1 updates them on
  // the refreshed rows only (each row's share subtracted before and added after); the other
  // cases evaluate them anew. A particle that loses its whole family is among the breaks, and
  // so is a Drucker-Prager law that yields (its trial states follow the rows' new H).
  for_each_case([](const Case& c) {
    const int d = c.d;
    const Families& f = c.families;
    // Nearest-neighbour families for the row update only.
    if (c.knn && (c.options.formulation != Formulation::classical || c.options.operator_order != 1)) return;
    for (const bool plastic : {false, true}) {
      CorrespondenceOptions o = c.options;
      if (plastic) {
        DruckerPrager dp = seed_biaxial_test(5).material;
        dp.cohesion = 20e3;
        o.plasticity = dp;
      }
      CorrespondenceModel model(c.cloud, f, material(d), o, c.surface);
      std::vector<test::Bond> breaks = test::random_bonds(f, c.cloud.size() / 8, 17);
      const std::size_t p = c.cloud.size() / 2;
      for (Offset k = f.begin(p); k < f.end(p); ++k) breaks.emplace_back(static_cast<ParticleId>(p), f.neighbors[k]);
      const auto u = test::random_field(model.dofs(), plastic ? 1e-2 : 1e-4, 21);
      std::vector<double> updated(u.size()), anew(u.size()), H(u.size() * d);
      model.internal_force(u.data(), updated.data());
      const double before = model.energy(u.data());
      const BondBreaks report = model.break_bonds(breaks, u.data(), updated.data());
      INFO((plastic ? "plastic" : "elastic") << ": " << report.broken << " bonds broken, " << report.rows.size()
                                             << " rows");
      REQUIRE(report.detached == std::vector<ParticleId>{static_cast<ParticleId>(p)});
      // last_gradient() is grad u at u on the changed model.
      model.gradient(u.data(), H.data());
      CHECK(relative(std::vector<double>(model.last_gradient(), model.last_gradient() + H.size()), H) <= 1e-12);
      const double after = model.energy(u.data());
      model.internal_force(u.data(), anew.data());
      CHECK(relative(updated, anew) <= 1e-12);
      CHECK(report.released != 0.0);  // of either sign: a row's K_i^-1 grows as it loses bonds
      CHECK(std::abs(report.released - (before - after)) <= 1e-12 * before);
    }
  });
}

TEST_CASE("a particle whose bonds all break is detached: no stress, no force, no NaN", "[models][refresh]") {
  for (const int d : {2, 3}) {
    const int side = d == 2 ? 9 : 6;
    const PointCloud cloud = test::lattice(d, side, 0.2);
    const Families f = radius_families(cloud, 2.015);
    CorrespondenceModel model(cloud, f, material(d), {Influence::inverse_square, 0.5, Formulation::classical});
    const std::size_t p = cloud.size() / 2;
    std::vector<test::Bond> breaks;
    for (Offset k = f.begin(p); k < f.end(p); ++k) breaks.emplace_back(static_cast<ParticleId>(p), f.neighbors[k]);
    const BondBreaks report = model.break_bonds(breaks);
    INFO("dim " << d);
    REQUIRE(report.detached == std::vector<ParticleId>{static_cast<ParticleId>(p)});
    const auto u = test::random_field(model.dofs(), 1e-4, 5);
    std::vector<double> force(u.size()), sigma;
    model.internal_force(u.data(), force.data());
    for (const double v : force) REQUIRE(std::isfinite(v));
    for (int a = 0; a < d; ++a) CHECK(force[p * d + a] == 0.0);
    model.stress3(u.data(), sigma);
    for (int k = 0; k < 9; ++k) CHECK(sigma[p * 9 + k] == 0.0);
    CHECK(std::isfinite(model.energy(u.data())));
  }
}

TEST_CASE("break_bonds refuses what it cannot refresh, before changing anything", "[models][refresh]") {
  const PointCloud cloud = test::lattice(2, 8, 0.2);
  const Families f = radius_families(cloud, 2.515);
  CorrespondenceOptions o{Influence::inverse_square, 0.5, Formulation::classical};
  o.operator_order = 2;
  CorrespondenceModel second(cloud, f, material(2), o);
  const test::Bond bond{0, f.neighbors[f.begin(0)]};
  CHECK_THROWS_AS(second.break_bonds({bond}), std::logic_error);
  CHECK(second.G().graph().broken() == 0);
  o.operator_order = 1;
  CorrespondenceModel first(cloud, f, material(2), o);
  CHECK_THROWS_AS(first.break_bonds({{0, static_cast<ParticleId>(cloud.size())}}), std::out_of_range);
  CHECK(first.G().graph().broken() == 0);
  CHECK(first.break_bonds({bond}).broken == 1);
}

TEST_CASE("break_bonds refuses a pair that is not a bond, and (i, i)", "[models][refresh]") {
  const PointCloud c = test::lattice(2, 8, 0.0);
  const Families f = radius_families(c, 2.015);
  CorrespondenceOptions o;
  o.formulation = Formulation::classical;
  CorrespondenceModel model(c, f, material(2), o);
  REQUIRE_THROWS_WITH(model.break_bonds({{0, 63}}), Catch::Contains("(0, 63) is not a bond"));
  REQUIRE_THROWS_WITH(model.break_bonds({{3, 3}}), Catch::Contains("(3, 3) is not a bond"));
  // A bond broken already is still a bond: breaking it again breaks nothing.
  REQUIRE(model.break_bonds({{0, 1}}).broken == 1);
  CHECK(model.break_bonds({{1, 0}}).broken == 0);
}

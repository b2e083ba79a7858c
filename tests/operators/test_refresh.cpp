// Broken bonds: refreshing the rows they touch gives what a build from scratch without those
// bonds gives (the operator, its transpose, every stabilization storage, the tangent rows),
// and a particle that loses its family is detached without a NaN.
#include <catch2/catch.hpp>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <set>

#include "../support/refresh.hpp"
#include "../support/clouds.hpp"
#include "perinom/materials/linear_elastic.hpp"
#include "perinom/neighbors/bond_graph.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/operators/fused_stabilization.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
#include "perinom/operators/stabilization.hpp"
#include "perinom/operators/stabilization_term.hpp"
#include "perinom/operators/tangent_rows.hpp"

using namespace perinom;

namespace {

using test::Bond;
using test::random_bonds;
using test::without;

using test::relative_difference;
using test::Rows;
using test::rows_difference;

Rows tangent_rows(const NonlocalOperator& G, const std::vector<double>& C, const std::vector<double>& volume,
                  const StabilizationTerm* S, std::vector<double>& row_sums) {
  Rows rows;
  const int d = G.dim();
  row_sums.assign(G.rows() * d, 0.0);
  for_each_tangent_row(G, PointwiseTangent{C.data(), 0, volume.data()}, S,
                       [&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
#pragma omp critical
                         for (std::size_t k = 0; k < cols.size(); ++k) {
                           std::vector<double> b(blocks.begin() + k * d * d, blocks.begin() + (k + 1) * d * d);
                           for (int a = 0; a < d; ++a)
                             for (int c = 0; c < d; ++c) row_sums[i * d + a] += std::abs(b[a * d + c]);
                           rows[{i, cols[k]}] = b;
                         }
                       });
  return rows;
}

Rows scalar_rows(const ScalarCsr& A) {
  Rows rows;
  for (std::size_t i = 0; i < A.rows(); ++i)
    for (Offset k = A.offsets[i]; k < A.offsets[i + 1]; ++k) rows[{i, A.cols[k]}] = {A.values[k]};
  return rows;
}

LinearElastic material(int dim) { return test::elastic_material(dim); }

struct Case {
  int dim;
  bool knn;
  int order;
};

constexpr double tolerance = 1e-13;
constexpr double modulus = 0.5 * 2.0 * 1.0;  // C_hg 2 mu

}  // namespace

TEST_CASE("refreshing the rows of broken bonds equals building without them", "[operators][refresh]") {
  for (const Case k : {Case{2, false, 1}, Case{2, true, 1}, Case{3, false, 1}, Case{3, true, 1}, Case{2, false, 2},
                       Case{2, true, 2}, Case{3, false, 2}, Case{3, true, 2}}) {
    const int d = k.dim;
    const PointCloud cloud = test::lattice(d, d == 2 ? 10 : 6, 0.3);
    const Families f = k.knn ? knn_families(cloud, d == 2 ? 16 : 36) : radius_families(cloud, 2.515);
    const BondWeights bw = bond_weights(cloud, f, Influence::inverse_square);
    const OperatorOptions options{k.order, k.order == 2};
    auto graph = std::make_shared<BondGraph>(f);
    NonlocalOperator G(cloud, graph, bw, options);
    // The stabilizations of every storage, built before the breaks and refreshed after.
    std::optional<Stabilization> S;
    std::optional<FusedStabilization> F;
    std::optional<Stabilization> S2;
    ScalarCsr S0;
    std::vector<double> area(cloud.size(), 1.0);
    // The same S behind the model's interface, at every assembly level the families allow.
    std::vector<AssemblyLevel> levels{AssemblyLevel::assembled, AssemblyLevel::matrix_free};
    if (!k.knn) levels.push_back(AssemblyLevel::fused);
    std::vector<std::unique_ptr<StabilizationTerm>> terms;
    if (k.order == 1)
      for (const AssemblyLevel level : levels) terms.push_back(make_stabilization(cloud, G, modulus, level));
    // Order 2: the matrix-free level keeps its fit and refreshes; the assembled one cannot.
    std::unique_ptr<StabilizationTerm> T2;
    if (k.order == 2) T2 = make_stabilization(cloud, G, bw, modulus, AssemblyLevel::matrix_free);
    if (k.order == 1) {
      S.emplace(cloud, G, modulus);
      F = FusedStabilization::make(cloud, G, modulus);
      REQUIRE(F.has_value() == !k.knn);
      S0 = assemble_stabilization(*S, cloud.size());
    } else {
      S2.emplace(cloud, G, bending_scale(G, 0.5, 1.0, area));
      S0 = assemble_stabilization(*S2, cloud.size());
    }

    const std::vector<Bond> breaks = random_bonds(f, cloud.size() / 8, 17);
    const std::vector<ParticleId> rows = graph->rows_touched(breaks);
    for (const auto& [i, j] : breaks) REQUIRE(graph->break_bond(i, j));
    G.refresh_rows(rows);
    if (S) S->refresh_rows(rows), refresh_stabilization(S0, *S, *graph, rows);
    if (F) F->refresh_rows(rows);
    for (auto& term : terms) term->refresh_rows(rows);
    if (T2) T2->refresh_rows(rows);
    if (S2) {
      S2->refresh_rows(rows);
      refresh_stabilization(S0, *S2, *graph, rows);
    }
    REQUIRE(G.detached().empty());

    const std::set<Bond> broken(breaks.begin(), breaks.end());
    const Families f2 = without(f, broken);
    const NonlocalOperator B(cloud, f2, bond_weights(cloud, f2, Influence::inverse_square), options);
    INFO("dim " << d << (k.knn ? " knn" : " radius") << " order " << k.order << ": " << breaks.size()
                << " bonds broken, " << rows.size() << " rows refreshed");

    // G, G^T and the divergence, on fields of 1 and d components.
    for (const int nc : {1, d}) {
      const auto u = test::random_field(cloud.size() * nc, 1.0, 5);
      const auto q = test::random_field(cloud.size() * nc * d, 1.0, 6);
      std::vector<double> a(q.size()), b(q.size()), at(u.size()), bt(u.size());
      G.apply(u.data(), nc, a.data());
      B.apply(u.data(), nc, b.data());
      CHECK(relative_difference(a, b) <= tolerance);
      G.apply_transpose(q.data(), nc, at.data());
      B.apply_transpose(q.data(), nc, bt.data());
      CHECK(relative_difference(at, bt) <= tolerance);
      // G^T is the adjoint of G: a check of the transposed entries independent of B.
      double lhs = 0.0, rhs = 0.0;
      for (std::size_t m = 0; m < q.size(); ++m) lhs += a[m] * q[m];
      for (std::size_t m = 0; m < u.size(); ++m) rhs += u[m] * at[m];
      CHECK(std::abs(lhs - rhs) <= 1e-12 * std::abs(lhs));
      G.divergence(q.data(), nc, at.data());
      B.divergence(q.data(), nc, bt.data());
      CHECK(relative_difference(at, bt) <= tolerance);
      if (k.order == 2) {
        const int m = G.hessian_terms();
        std::vector<double> h(cloud.size() * nc * m), hb(h.size());
        G.apply(u.data(), nc, h.data(), Derivative::hessian);
        B.apply(u.data(), nc, hb.data(), Derivative::hessian);
        CHECK(relative_difference(h, hb) <= tolerance);
        G.apply_transpose(hb.data(), nc, at.data(), nullptr, Derivative::hessian);
        B.apply_transpose(hb.data(), nc, bt.data(), nullptr, Derivative::hessian);
        CHECK(relative_difference(at, bt) <= tolerance);
      }
    }

    // The stabilizations, every storage, and the tangent rows with their ADR bound.
    const auto u = test::random_field(cloud.size() * d, 1.0, 7);
    std::vector<double> C(d * d * d * d), sums_a, sums_b;
    material(d).tangent(C.data());
    if (k.order == 1) {
      const Stabilization SB(cloud, B, modulus);
      std::vector<double> H(cloud.size() * d * d), Ba(H.size()), Bb(H.size()), ra(u.size()), rb(u.size());
      B.apply(u.data(), d, H.data());
      S->bond_terms(u.data(), H.data(), Ba.data(), ra.data());
      SB.bond_terms(u.data(), H.data(), Bb.data(), rb.data());
      CHECK(relative_difference(Ba, Bb) <= tolerance);
      CHECK(relative_difference(ra, rb) <= tolerance);
      std::vector<double> da(u.size(), 0.0), db(u.size(), 0.0);
      S->add_direct(u.data(), H.data(), ra.data(), da.data());
      SB.add_direct(u.data(), H.data(), rb.data(), db.data());
      CHECK(relative_difference(da, db) <= tolerance);
      CHECK(rows_difference(scalar_rows(S0), scalar_rows(assemble_stabilization(SB, cloud.size()))) <= tolerance);
      if (F) {
        const auto FB = FusedStabilization::make(cloud, B, modulus);
        std::vector<double> Ha(H.size()), Hb(H.size()), la(u.size()), lb(u.size());
        F->gradient_and_laplacian(u.data(), Ha.data(), la.data());
        FB->gradient_and_laplacian(u.data(), Hb.data(), lb.data());
        CHECK(relative_difference(Ha, Hb) <= tolerance);
        CHECK(relative_difference(la, lb) <= tolerance);
        F->tensor_terms(H.data(), Ba.data());
        FB->tensor_terms(H.data(), Bb.data());
        CHECK(relative_difference(Ba, Bb) <= tolerance);
      }
      // Each level refreshed against the same level built without the bonds: S u and the
      // tangent rows with their ADR bound.
      for (std::size_t t = 0; t < terms.size(); ++t) {
        INFO("assembly level " << int(levels[t]));
        const auto TB = make_stabilization(cloud, B, modulus, levels[t]);
        std::vector<double> Hw(H.size()), Sa(u.size()), Sb(u.size());
        terms[t]->apply(u.data(), Hw.data(), Sa.data());
        TB->apply(u.data(), Hw.data(), Sb.data());
        CHECK(relative_difference(Sa, Sb) <= tolerance);
        const Rows ta = tangent_rows(G, C, cloud.volume, terms[t].get(), sums_a);
        const Rows tb = tangent_rows(B, C, cloud.volume, TB.get(), sums_b);
        CHECK(rows_difference(ta, tb) <= tolerance);
        CHECK(relative_difference(sums_a, sums_b) <= tolerance);
      }
    } else {
      Stabilization SB(cloud, B, bending_scale(B, 0.5, 1.0, area));
      const ScalarCsr S0b = assemble_stabilization(SB, cloud.size());
      CHECK(rows_difference(scalar_rows(S0), scalar_rows(S0b)) <= tolerance);
      const auto w = test::random_field(cloud.size(), 1.0, 8);
      std::vector<double> g(cloud.size() * d), h(cloud.size() * G.hessian_terms());
      B.apply(w.data(), 1, g.data());
      B.apply(w.data(), 1, h.data(), Derivative::hessian);
      std::vector<double> fa(cloud.size(), 0.0), fb(cloud.size(), 0.0);
      S2->add_force(w.data(), 1, g.data(), h.data(), fa.data());
      SB.add_force(w.data(), 1, g.data(), h.data(), fb.data());
      CHECK(relative_difference(fa, fb) <= tolerance);
      CHECK(std::abs(S2->energy(w.data(), 1, g.data(), h.data()) - SB.energy(w.data(), 1, g.data(), h.data())) <=
            tolerance * SB.energy(w.data(), 1, g.data(), h.data()));
      // The order-2 matrix-free level, refreshed, against the same built without the bonds:
      // S u and the tangent rows; and against the assembled level (the same S).
      const Families& fb2 = B.graph().families();
      const auto TB2 = make_stabilization(cloud, B, bond_weights(cloud, fb2, Influence::inverse_square), modulus,
                                          AssemblyLevel::matrix_free);
      const auto TB2s = make_stabilization(cloud, B, bond_weights(cloud, fb2, Influence::inverse_square), modulus,
                                           AssemblyLevel::assembled);
      CHECK_FALSE(TB2s->refreshable());
      std::vector<double> Hw(cloud.size() * d * d), Sa(u.size()), Sb(u.size()), Ss(u.size());
      T2->apply(u.data(), Hw.data(), Sa.data());
      TB2->apply(u.data(), Hw.data(), Sb.data());
      TB2s->apply(u.data(), Hw.data(), Ss.data());
      CHECK(relative_difference(Sa, Sb) <= tolerance);
      CHECK(relative_difference(Ss, Sb) <= 1e-12);
      CHECK(rows_difference(tangent_rows(G, C, cloud.volume, T2.get(), sums_a),
                            tangent_rows(B, C, cloud.volume, TB2.get(), sums_b)) <= tolerance);
      CHECK(relative_difference(sums_a, sums_b) <= tolerance);
      const auto Ta = stored_stabilization(G, S0, "S");
      const auto Tb = stored_stabilization(B, S0b, "S");
      CHECK_THROWS_AS(stored_stabilization(G, S0, "S")->refresh_rows(rows), std::logic_error);
      const Rows ta = tangent_rows(G, C, cloud.volume, Ta.get(), sums_a);
      const Rows tb = tangent_rows(B, C, cloud.volume, Tb.get(), sums_b);
      CHECK(rows_difference(ta, tb) <= tolerance);
      CHECK(relative_difference(sums_a, sums_b) <= tolerance);
    }
  }
}

TEST_CASE("a particle whose bonds break one by one ends detached, with no NaN", "[operators][refresh]") {
  for (const int order : {1, 2}) {
    for (const int d : {2, 3}) {
      const PointCloud cloud = test::lattice(d, d == 2 ? 9 : 6, 0.2);
      const Families f = radius_families(cloud, 2.515);
      const BondWeights bw = bond_weights(cloud, f, Influence::inverse_square);
      auto graph = std::make_shared<BondGraph>(f);
      NonlocalOperator G(cloud, graph, bw, OperatorOptions{order, order == 2});
      std::optional<Stabilization> S;
      std::optional<FusedStabilization> F;
      if (order == 1) S.emplace(cloud, G, modulus), F = FusedStabilization::make(cloud, G, modulus);
      const ParticleId p = static_cast<ParticleId>(cloud.size() / 2);  // an interior particle
      const LinearElastic law = material(d);
      const auto u = test::random_field(cloud.size() * d, 1e-3, 9);
      std::vector<double> H(cloud.size() * d * d), Q(H.size()), force(u.size()), r(u.size()), lap(u.size());
      bool was_detached = false;
      for (Offset k = f.begin(p); k < f.end(p); ++k) {
        const ParticleId j = f.neighbors[k];
        const auto rows = graph->rows_touched({{p, j}});
        REQUIRE(graph->break_bond(p, j));
        G.refresh_rows(rows);
        if (S) S->refresh_rows(rows), F->refresh_rows(rows);
        // The weak-form force with the stabilization, as the correspondence model makes it.
        if (F) F->gradient_and_laplacian(u.data(), H.data(), lap.data());
        else G.apply(u.data(), d, H.data());
        for (std::size_t i = 0; i < cloud.size(); ++i) law.stress(H.data() + i * d * d, Q.data() + i * d * d);
        G.apply_transpose(Q.data(), d, force.data());
        if (S) {
          S->bond_terms(u.data(), H.data(), Q.data(), r.data());
          S->add_direct(u.data(), H.data(), r.data(), force.data());
        }
        for (const double v : H) REQUIRE(std::isfinite(v));
        for (const double v : force) REQUIRE(std::isfinite(v));
        for (const double v : lap) REQUIRE(std::isfinite(v));
        if (G.is_detached(p)) {
          was_detached = true;
          // No gradient, so no stress, at p; and p's transposed entries are zero.
          for (int c = 0; c < d * d; ++c) CHECK(H[p * d * d + c] == 0.0);
          G.visit_row(p, [&](ParticleId, const double* g) {
            for (int b = 0; b < d; ++b) CHECK(g[b] == 0.0);
          });
          REQUIRE(S.has_value() == (order == 1));
          if (S) CHECK(S->scaled_coefficients()[p] == 0.0);
        }
      }
      INFO("order " << order << " dim " << d);
      CHECK(was_detached);
      CHECK(G.is_detached(p));
      CHECK(std::find(G.detached().begin(), G.detached().end(), p) != G.detached().end());
    }
  }
}

TEST_CASE("the bond graph breaks both directions and names the rows it touches", "[operators][refresh]") {
  const PointCloud cloud = test::lattice(2, 6, 0.3);
  const Families f = knn_families(cloud, 6);  // not symmetric
  BondGraph g(f);
  CHECK_FALSE(g.symmetric());
  CHECK(BondGraph(radius_families(cloud, 1.5)).symmetric());
  // The dual entry of every bond lists it transposed.
  for (std::size_t i = 0; i < g.rows(); ++i)
    for (Offset k = g.begin(i); k < g.end(i); ++k) {
      const Offset t = g.dual_entry(k);
      CHECK(t >= g.dual_begin(g.col(k)));
      CHECK(t < g.dual_end(g.col(k)));
      CHECK(g.dual_col(t) == static_cast<ParticleId>(i));
    }
  // A one-way bond touches one row, a two-way bond two.
  int one_way = 0, two_way = 0;
  for (std::size_t i = 0; i < g.rows(); ++i)
    for (Offset k = g.begin(i); k < g.end(i); ++k) {
      const ParticleId j = g.col(k);
      const auto rows = g.rows_touched({{static_cast<ParticleId>(i), j}});
      const bool back = g.find(j, static_cast<ParticleId>(i)) >= 0;
      CHECK(rows.size() == (back ? 2u : 1u));
      (back ? two_way : one_way) += 1;
    }
  CHECK(one_way > 0);
  CHECK(two_way > 0);
  const ParticleId j = g.col(g.begin(0));
  CHECK(g.break_bond(0, j));
  CHECK_FALSE(g.alive(g.begin(0)));
  CHECK_FALSE(g.break_bond(0, j));  // nothing left to break
  CHECK(g.rows_touched({{0, j}}).empty());
  int live = 0;
  g.for_each_live(0, [&](Offset, ParticleId) { ++live; });
  CHECK(live == g.end(0) - g.begin(0) - 1);
}

TEST_CASE("the consistent gradient's given weights refuse a refresh", "[operators][refresh]") {
  const PointCloud cloud = test::lattice(2, 6, 0.3);
  const Families f = radius_families(cloud, 2.015);
  const NonlocalOperator G(cloud, f, bond_weights(cloud, f, Influence::inverse_square));
  std::vector<double> g(G.bonds() * 2, 0.0);
  NonlocalOperator given(G.shared_graph(), 2, g);
  CHECK_FALSE(given.refreshable());
  CHECK_THROWS_AS(given.refresh_rows({0}), std::logic_error);
  CHECK_THROWS_WITH(given.refresh_rows({0}), Catch::Contains("not implemented"));
}

TEST_CASE("an interleaved multi-field vector is used in place, 4 components in 3-D too", "[operators]") {
  for (const int d : {2, 3}) {
    const PointCloud cloud = test::lattice(d, d == 2 ? 8 : 5, 0.3);
    const Families f = radius_families(cloud, 2.015);
    const NonlocalOperator G(cloud, f, bond_weights(cloud, f, Influence::inverse_square));
    const std::size_t n = cloud.size();
    for (const int nc : {1, d, d + 1, 9}) {
      // A vector of nc + 2 values per particle: the field sits at offset 1, stride nc + 2.
      const int stride = nc + 2;
      const auto all = test::random_field(n * stride, 1.0, 11);
      std::vector<double> packed(n * nc);
      for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < nc; ++c) packed[i * nc + c] = all[i * stride + 1 + c];
      std::vector<double> a(n * nc * d), b(a.size());
      G.apply(all.data() + 1, FieldLayout{nc, stride}, a.data());
      G.apply(packed.data(), nc, b.data());
      INFO("dim " << d << " components " << nc);
      CHECK(relative_difference(a, b) <= 1e-15);
      // The transposed product and the divergence write in place, leaving the other values.
      const auto q = test::random_field(n * nc * d, 1.0, 12);
      std::vector<double> out(n * stride, -3.0), ref(n * nc), div(n * stride, -3.0), dref(n * nc);
      G.apply_transpose(q.data(), FieldLayout{nc, stride}, out.data() + 1);
      G.apply_transpose(q.data(), nc, ref.data());
      G.divergence(q.data(), FieldLayout{nc, stride}, div.data() + 1);
      G.divergence(q.data(), nc, dref.data());
      for (std::size_t i = 0; i < n; ++i) {
        CHECK(out[i * stride] == -3.0);
        CHECK(div[i * stride + stride - 1] == -3.0);
        for (int c = 0; c < nc; ++c) {
          CHECK(out[i * stride + 1 + c] == Approx(ref[i * nc + c]).margin(1e-14));
          CHECK(div[i * stride + 1 + c] == Approx(dref[i * nc + c]).margin(1e-14));
        }
      }
    }
  }
}

TEST_CASE("the second-order stabilization energy gives the same bits on 1 and 2 threads", "[operators][second_order]") {
  // Enough particles for parallel_sums to use the team (core/parallel.hpp: 16384).
  const PointCloud cloud = test::lattice(2, 130, 0.3);
  const Families f = knn_families(cloud, 14);
  const NonlocalOperator D(cloud, f, bond_weights(cloud, f, Influence::inverse_square), OperatorOptions{2, true});
  const std::vector<double> area(cloud.size(), 1.0);
  const Stabilization S(cloud, D, bending_scale(D, 0.5, 1.0, area));
  const auto w = test::random_field(cloud.size(), 1.0, 13);
  std::vector<double> g(cloud.size() * 2), h(cloud.size() * 3);
  D.apply(w.data(), 1, g.data());
  D.apply(w.data(), 1, h.data(), Derivative::hessian);
  double energy[2];
  const int before = omp_get_max_threads();
  for (const int t : {0, 1}) {
    omp_set_num_threads(t + 1);
    energy[t] = S.energy(w.data(), 1, g.data(), h.data());
  }
  omp_set_num_threads(before);
  CHECK(std::memcmp(&energy[0], &energy[1], sizeof(double)) == 0);
}

TEST_CASE("a stored S0 updated by the blocks of the refreshed centres equals its rows assembled anew",
          "[operators][refresh]") {
  // What CorrespondenceModel::break_bonds runs (StabilizationTerm::refresh_rows around the
  // change): S0 minus the blocks of the touched centres, the breaks and G's refresh, plus
  // their blocks. Three rounds, the last one detaching a particle.
  for (const Case k : {Case{2, false, 1}, Case{2, true, 1}, Case{3, false, 1}, Case{3, true, 1}}) {
    const int d = k.dim;
    INFO("dim " << d << (k.knn ? " knn" : " radius"));
    const PointCloud cloud = test::lattice(d, d == 2 ? 12 : 6, 0.3);
    const Families f = k.knn ? knn_families(cloud, d == 2 ? 16 : 36) : radius_families(cloud, 2.515);
    auto graph = std::make_shared<BondGraph>(f);
    NonlocalOperator G(cloud, graph, bond_weights(cloud, f, Influence::inverse_square), OperatorOptions{1, false});
    const auto term = make_stabilization(cloud, G, modulus, AssemblyLevel::assembled);
    for (int round = 0; round < 3; ++round) {
      std::vector<Bond> breaks = random_bonds(f, cloud.size() / 6, 40 + round);
      if (round == 2) {
        const ParticleId p = static_cast<ParticleId>(cloud.size() / 2);
        for (Offset b = f.offsets[p]; b < f.offsets[p + 1]; ++b) breaks.emplace_back(p, f.neighbors[b]);
      }
      const std::vector<ParticleId> rows = graph->rows_touched(breaks);
      term->refresh_rows(rows, [&] {
        for (const auto& [i, j] : breaks) graph->break_bond(i, j);
        G.refresh_rows(rows);
      });
      const Stabilization anew(cloud, G, modulus);
      const ScalarCsr S0 = assemble_stabilization(anew, cloud.size());
      CHECK(rows_difference(scalar_rows(*term->stored()), scalar_rows(S0)) <= tolerance);
    }
    CHECK_FALSE(G.detached().empty());
  }
}

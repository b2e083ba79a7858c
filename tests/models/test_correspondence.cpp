#include <catch2/catch.hpp>
#include <omp.h>

#include <cstring>
#include <memory>
#include <set>

#include "../support/clouds.hpp"
#include "../support/refresh.hpp"
#include "perinom/geometry/surface.hpp"
#include "perinom/core/error.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/operators/tangent_rows.hpp"

using namespace perinom;

namespace {

LinearElastic material(int dim, PlaneCondition plane) {
  LinearElastic m;
  m.E = 30e6;
  m.nu = 0.25;
  m.density = 2000;
  m.dim = dim;
  m.plane = plane;
  return m;
}

struct Case {
  int dim;
  PlaneCondition plane;
  bool knn;
};

const Case cases[] = {{2, PlaneCondition::strain, false}, {2, PlaneCondition::stress, true},
                      {3, PlaneCondition::none, false}, {3, PlaneCondition::none, true}};

Families families(const PointCloud& c, bool knn) {
  return knn ? knn_families(c, c.dim == 2 ? 12 : 30) : radius_families(c, 2.015);
}

}  // namespace

TEST_CASE("the assembled force equals the bond loop of seed 000 eq. 16/19, damaged too", "[models]") {
  for (const Case& k : cases)
  for (const bool damaged : {false, true}) {
    const PointCloud c = test::lattice(k.dim, k.dim == 2 ? 9 : 5, 0.3);
    const Families intact = families(c, k.knn);
    const LinearElastic mat = material(k.dim, k.plane);
    CorrespondenceModel model(c, intact, mat, {Influence::inverse_distance, 0.0});
    // Damaged: bonds broken through the model; the loop runs over the live bonds only.
    const std::vector<test::Bond> breaks = damaged ? test::random_bonds(intact, c.size() / 8, 31) : std::vector<test::Bond>{};
    if (damaged) REQUIRE(model.break_bonds(breaks).detached.empty());
    const Families f = test::without(intact, std::set<test::Bond>(breaks.begin(), breaks.end()));
    const int d = k.dim, d2 = d * d;
    const auto u = test::random_field(c.size() * d, 1e-4, 8);
    std::vector<double> fint(u.size());
    model.internal_force(u.data(), fint.data());

    // Straight from the seed: K_i, F_i = I + sum_j (u_j - u_i) (x) w V_j K_i^-1 xi_ij,
    // T_ij = w_ij P_i K_i^-1 xi_ij, L_i = sum_j (T_ij V_j - T_ji V_j) and f_int = -V L.
    const BondWeights bw = bond_weights(c, f, Influence::inverse_distance);
    std::vector<double> P(c.size() * d2);
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double* Ki = bw.shape_inverse.data() + i * d2;
      double H[9] = {};
      for (Offset b = f.begin(i); b < f.end(i); ++b) {
        const std::size_t j = f.neighbors[b];
        for (int a = 0; a < d; ++a)
          for (int e = 0; e < d; ++e)
            for (int g = 0; g < d; ++g)
              H[a * d + e] += (u[j * d + a] - u[i * d + a]) * bw.wv[b] * Ki[e * d + g] * (c.x[j * d + g] - c.x[i * d + g]);
      }
      mat.stress(H, P.data() + i * d2);
    }
    std::vector<double> L(u.size(), 0.0);
    for (std::size_t i = 0; i < c.size(); ++i)
      for (Offset b = f.begin(i); b < f.end(i); ++b) {
        const std::size_t j = f.neighbors[b];
        // T_ij V_j acts on i; its reaction -T_ij V_i acts on j (the j-sum of eq. 16 over H'_j).
        double t[3] = {};
        const double* Ki = bw.shape_inverse.data() + i * d2;
        for (int a = 0; a < d; ++a)
          for (int e = 0; e < d; ++e)
            for (int g = 0; g < d; ++g)
              t[a] += bw.wv[b] / c.volume[j] * P[i * d2 + a * d + e] * Ki[e * d + g] * (c.x[j * d + g] - c.x[i * d + g]);
        for (int a = 0; a < d; ++a) {
          L[i * d + a] += t[a] * c.volume[j];
          L[j * d + a] -= t[a] * c.volume[i];
        }
      }
    double err = 0.0;
    for (std::size_t k2 = 0; k2 < u.size(); ++k2) err = std::max(err, std::abs(fint[k2] + c.volume[k2 / d] * L[k2]));
    INFO("dim " << d << (k.knn ? " knn" : " radius") << (damaged ? ", damaged" : ""));
    CHECK(err <= 1e-12 * test::max_abs(fint));
  }
}

TEST_CASE("the internal force is the derivative of the stored energy", "[models]") {
  for (const Case& k : cases) {
    const PointCloud c = test::lattice(k.dim, k.dim == 2 ? 8 : 4, 0.3);
    CorrespondenceModel model(c, families(c, k.knn), material(k.dim, k.plane), {Influence::inverse_square, 0.5});
    const auto u = test::random_field(model.dofs(), 1e-4, 2);
    std::vector<double> f(u.size());
    model.internal_force(u.data(), f.data());
    for (int dir = 0; dir < 4; ++dir) {
      const auto v = test::random_field(u.size(), 1.0, 100 + dir);
      const double h = 1e-6;
      auto up = u, um = u;
      for (std::size_t m = 0; m < u.size(); ++m) up[m] += h * v[m], um[m] -= h * v[m];
      const double fd = (model.energy(up.data()) - model.energy(um.data())) / (2 * h);
      double fv = 0.0;
      for (std::size_t m = 0; m < u.size(); ++m) fv += f[m] * v[m];
      CHECK(fv == Approx(fd).epsilon(1e-7));
    }
  }
}

TEST_CASE("the assembled tangent rows equal the derivative of the force", "[models][operators]") {
  for (const Case& k : cases)
  for (const Formulation form : {Formulation::classical, Formulation::improved, Formulation::strong}) {
    const int side = k.dim == 2 ? 9 : 5;
    const PointCloud c = test::lattice(k.dim, side, 0.3);
    BoxGeometry box;
    box.dim = k.dim;
    for (int a = 0; a < k.dim; ++a) box.max[a] = side;
    // A band of 2 spacings leaves both strong (E) and weak (D) rows in these small clouds.
    Surface surface = find_surface(box, c, form == Formulation::strong ? INFINITY : 2.0);
    if (form == Formulation::improved) REQUIRE(!surface.interior.empty());
    CorrespondenceModel model(c, families(c, k.knn), material(k.dim, k.plane),
                              {Influence::inverse_square, 0.5, form}, surface);
    const int d = k.dim;
    const std::size_t n = model.dofs();
    // The model is linear: column m of K is f(e_m).
    std::vector<double> K(n * n), e(n, 0.0), col(n);
    for (std::size_t m = 0; m < n; ++m) {
      e[m] = 1.0;
      model.internal_force(e.data(), col.data());
      e[m] = 0.0;
      for (std::size_t r = 0; r < n; ++r) K[r * n + m] = col[r];
    }
    std::vector<double> C(d * d * d * d);
    model.material().tangent(C.data());
    std::vector<double> assembled(n * n, 0.0);
    const StrongRows strong{model.surface().in_band.data(), model.surface().normal_over_h.data()};
    for_each_tangent_row(model.G(), {C.data(), 0, model.volume().data()}, model.stabilization(),
                         [&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
                           for (std::size_t q = 0; q < cols.size(); ++q)
                             for (int a = 0; a < d; ++a)
                               for (int b = 0; b < d; ++b)
                                 assembled[(i * d + a) * n + cols[q] * d + b] = blocks[(q * d + a) * d + b];
                         },
                         form == Formulation::classical ? nullptr : &strong);
    INFO("dim " << d << " formulation " << int(form));
    double err = 0.0, scale = test::max_abs(K);
    for (std::size_t m = 0; m < n * n; ++m) err = std::max(err, std::abs(K[m] - assembled[m]));
    CHECK(err <= 1e-11 * scale);
    const auto sums = model.stiffness_row_sums();
    for (std::size_t r = 0; r < n; ++r) {
      double s = 0.0;
      for (std::size_t m = 0; m < n; ++m) s += std::abs(K[r * n + m]);
      CHECK(sums[r] == Approx(s).epsilon(1e-10));
    }
  }
}

TEST_CASE("the force is bitwise independent of the thread count", "[models]") {
  // Each row is summed in a fixed order by one thread (gathers, no atomics, no reductions).
  const PointCloud c = test::lattice(3, 9, 0.3);
  BoxGeometry box;
  box.dim = 3;
  box.max = {9, 9, 9};
  for (const Formulation form : {Formulation::classical, Formulation::improved}) {
    CorrespondenceModel model(c, radius_families(c, 2.015), material(3, PlaneCondition::none),
                              {Influence::inverse_square, 0.5, form}, find_surface(box, c, 4.03));
    const auto u = test::random_field(model.dofs(), 1e-4, 12);
    std::vector<double> one(u.size()), two(u.size());
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    model.internal_force(u.data(), one.data());
    omp_set_num_threads(2);
    model.internal_force(u.data(), two.data());
    omp_set_num_threads(threads);
    CHECK(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)) == 0);
  }
}

TEST_CASE("the fused, matrix-free and assembled stabilizations give the same force", "[models]") {
  using Storage = StabilizationStorage;
  for (const Case& k : cases)
    for (const Formulation form : {Formulation::classical, Formulation::improved}) {
      const int side = k.dim == 2 ? 10 : 6;
      const PointCloud c = test::lattice(k.dim, side, 0.3);
      BoxGeometry box;
      box.dim = k.dim;
      for (int a = 0; a < k.dim; ++a) box.max[a] = side;
      const Families f = families(c, k.knn);
      auto make = [&](Storage storage) {
        CorrespondenceOptions o{Influence::inverse_square, 0.5, form};
        o.stabilization_storage = storage;
        return std::make_unique<CorrespondenceModel>(c, f, material(k.dim, k.plane), o, find_surface(box, c, 2.0));
      };
      INFO("dim " << k.dim << (k.knn ? " knn" : " radius") << " formulation " << int(form));
      const auto stored = make(Storage::assembled);
      REQUIRE(stored->stabilization()->level() == AssemblyLevel::assembled);
      const auto u = test::random_field(stored->dofs(), 1e-4, 21);
      std::vector<double> fs(u.size()), fo(u.size());
      stored->internal_force(u.data(), fs.data());
      // k nearest neighbours make asymmetric families: no fused S, and auto falls back.
      if (k.knn) {
        CHECK_THROWS_AS(make(Storage::fused), InputError);
        CHECK(make(Storage::automatic)->stabilization()->level() == AssemblyLevel::assembled);
      } else {
        CHECK(make(Storage::automatic)->stabilization()->level() == AssemblyLevel::fused);
      }
      for (const Storage other : {Storage::matrix_free, Storage::fused}) {
        if (other == Storage::fused && k.knn) continue;
        const auto model = make(other);
        REQUIRE(model->stabilization()->level() ==
                (other == Storage::fused ? AssemblyLevel::fused : AssemblyLevel::matrix_free));
        model->internal_force(u.data(), fo.data());
        double err = 0.0;
        for (std::size_t m = 0; m < u.size(); ++m) err = std::max(err, std::abs(fs[m] - fo[m]));
        INFO("storage " << int(other));
        CHECK(err <= 1e-11 * test::max_abs(fs));
        CHECK(model->energy(u.data()) == Approx(stored->energy(u.data())).epsilon(1e-11));
      }
    }
}

TEST_CASE("order 2: the matrix-free and assembled stabilizations give the same force, energy and rows", "[models]") {
  for (const Case& k : cases) {
    const int side = k.dim == 2 ? 9 : 6;
    const PointCloud c = test::lattice(k.dim, side, 0.3);
    const Families f = k.knn ? knn_families(c, k.dim == 2 ? 16 : 36) : radius_families(c, 2.515);
    auto make = [&](StabilizationStorage storage) {
      CorrespondenceOptions o{Influence::inverse_square, 0.5, Formulation::classical};
      o.operator_order = 2;
      o.stabilization_storage = storage;
      return std::make_unique<CorrespondenceModel>(c, f, material(k.dim, k.plane), o);
    };
    const auto stored = make(StabilizationStorage::automatic);
    const auto free = make(StabilizationStorage::matrix_free);
    INFO("dim " << k.dim << (k.knn ? " knn" : " radius"));
    REQUIRE(stored->stabilization()->level() == AssemblyLevel::assembled);
    REQUIRE(free->stabilization()->level() == AssemblyLevel::matrix_free);
    CHECK_THROWS_AS(make(StabilizationStorage::fused), InputError);
    const auto u = test::random_field(stored->dofs(), 1e-4, 23);
    std::vector<double> fs(u.size()), fo(u.size());
    stored->internal_force(u.data(), fs.data());
    free->internal_force(u.data(), fo.data());
    double err = 0.0;
    for (std::size_t m = 0; m < u.size(); ++m) err = std::max(err, std::abs(fs[m] - fo[m]));
    CHECK(err <= 1e-11 * test::max_abs(fs));
    CHECK(free->energy(u.data()) == Approx(stored->energy(u.data())).epsilon(1e-11));
    std::vector<double> ks = stored->stiffness_row_sums(), ko = free->stiffness_row_sums();
    for (std::size_t m = 0; m < ks.size(); ++m) CHECK(ko[m] == Approx(ks[m]).epsilon(1e-11));
  }
}

TEST_CASE("the model refuses families of another cloud and a neighbour beyond the cloud", "[models]") {
  const PointCloud c = test::lattice(2, 6, 0.0), finer = test::lattice(2, 8, 0.0);
  const LinearElastic m = material(2, PlaneCondition::strain);
  REQUIRE_THROWS_WITH(CorrespondenceModel(c, radius_families(finer, 2.015), m, {}),
                      Catch::Contains("Families: rows for 64 particles on a cloud of 36"));
  REQUIRE_THROWS_WITH(CorrespondenceModel(finer, radius_families(c, 2.015), m, {}),
                      Catch::Contains("Families: rows for 36 particles on a cloud of 64"));
  Families f = radius_families(c, 2.015);
  f.neighbors[f.begin(3)] = 100000;
  REQUIRE_THROWS_WITH(CorrespondenceModel(c, f, m, {}),
                      Catch::Contains("particle 3 has neighbour 100000, beyond the 36 particles"));
  Families self = radius_families(c, 2.015);
  self.neighbors[self.begin(4)] = 4;
  REQUIRE_THROWS_WITH(CorrespondenceModel(c, self, m, {}), Catch::Contains("particle 4 is its own neighbour"));
}

TEST_CASE("the model refuses a material of another dimension, bad constants and a negative stabilization",
          "[models]") {
  const PointCloud c = test::lattice(2, 6, 0.0);
  const Families f = radius_families(c, 2.015);
  REQUIRE_THROWS_WITH(CorrespondenceModel(c, f, material(3, PlaneCondition::none), {}),
                      Catch::Contains("LinearElastic::dim = 3 on a 2-D cloud"));
  LinearElastic m = material(2, PlaneCondition::strain);
  m.nu = 0.5;
  REQUIRE_THROWS_WITH(CorrespondenceModel(c, f, m, {}), Catch::Contains("LinearElastic::nu = 0.5"));
  m = material(2, PlaneCondition::strain);
  m.E = -1e9;
  REQUIRE_THROWS_AS(CorrespondenceModel(c, f, m, {}), InputError);
  CorrespondenceOptions o;
  o.stabilization = -1.0;
  REQUIRE_THROWS_WITH(CorrespondenceModel(c, f, material(2, PlaneCondition::strain), o),
                      Catch::Contains("CorrespondenceOptions::stabilization"));
}

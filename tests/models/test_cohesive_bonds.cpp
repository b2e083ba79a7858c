// Softening bonds (models/cohesive_bonds.hpp, damage.fracture_energy): the force is the
// energy's derivative where the law is elastic, unloading is secant, a spent bond has
// dissipated F0 eta_u / 2, the bonds crossing a flat crack through a lattice hold G_f per unit
// area (to the lattice's count in the crack's direction, along an axis or inclined), and through the model the
// breaking update of a force, the released energy and the stiffness bound stay those of a
// model evaluated anew.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "../support/clouds.hpp"
#include "../support/refresh.hpp"
#include "perinom/models/cohesive_bonds.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

namespace {

const CohesiveLaw law{1.0e6, 50.0, 30.0e9};  // f_t (Pa), G_f (J/m^2), E (Pa)

/// Every bond (i < j) of the families.
std::vector<std::pair<ParticleId, ParticleId>> all_pairs(const Families& f) {
  std::vector<std::pair<ParticleId, ParticleId>> out;
  for (std::size_t i = 0; i < f.particles(); ++i)
    for (Offset k = f.begin(i); k < f.end(i); ++k)
      if (std::size_t(f.neighbors[k]) > i) out.emplace_back(ParticleId(i), f.neighbors[k]);
  return out;
}

/// A lattice of spacing h (volume h^d each) and its radius families at 3.015 h.
struct Lattice {
  PointCloud cloud;
  Families families;
  Lattice(int d, int n, double h) : cloud(test::lattice(d, n, 0.0)) {
    for (double& x : cloud.x) x *= h;
    for (double& v : cloud.volume) v = std::pow(h, d);
    families = radius_families(cloud, 3.015 * h);
  }
};

}  // namespace

TEST_CASE("a softening bond's force is its energy's derivative while elastic, closed pushes back, and unloads to the origin",
          "[models][cohesive]") {
  for (const int d : {2, 3}) {
    INFO("dim " << d);
    const Lattice l(d, d == 2 ? 8 : 5, 1e-3);
    const BondGraph graph(l.families);
    CohesiveBonds bonds(d, l.cloud.x, l.cloud.volume, graph, law);
    bonds.add(all_pairs(l.families));
    // Openings below eta_e = |xi| f_t / E (3.3e-8 m for a bond of one spacing): the rising branch.
    const std::vector<double> u = test::random_field(l.cloud.size() * d, 2e-9, 5);
    std::vector<double> f(u.size(), 0.0);
    bonds.add_force(u.data(), f.data());
    const double h = 1e-13;
    double worst = 0.0, largest = test::max_abs(f);
    for (std::size_t k = 0; k < u.size(); k += 7) {
      std::vector<double> up = u, um = u;
      up[k] += h, um[k] -= h;
      const double fd = (bonds.energy(up.data()) - bonds.energy(um.data())) / (2 * h);
      worst = std::max(worst, std::abs(fd - f[k]));
    }
    CHECK(largest > 0.0);
    CHECK(worst <= 1e-5 * largest);
    // Closed, a bond pushes back as it pulled (the faces in contact): on the rising branch
    // the force at -u is the opposite of that at u (it was zero for the closed ones before).
    std::vector<double> minus = u, f_minus(u.size(), 0.0);
    for (double& x : minus) x = -x;
    bonds.add_force(minus.data(), f_minus.data());
    for (std::size_t k = 0; k < f.size(); ++k) CHECK(f_minus[k] == Approx(-f[k]).margin(1e-12 * largest));
    // Past the peak, committed: at half the state every bond carries half its force.
    std::vector<double> big = u;
    for (double& x : big) x *= 4000.0;  // openings up to ~2e-5 m: softening, below eta_u
    bonds.commit(big.data());
    CHECK(bonds.dissipated() > 0.0);
    std::vector<double> half = big, f1(u.size(), 0.0), f2(u.size(), 0.0);
    for (double& x : half) x *= 0.5;
    bonds.add_force(big.data(), f1.data());
    bonds.add_force(half.data(), f2.data());
    for (std::size_t k = 0; k < f1.size(); ++k) CHECK(f2[k] == Approx(0.5 * f1[k]).margin(1e-12 * test::max_abs(f1)));
    // Committing a smaller state changes nothing.
    const double before = bonds.dissipated();
    bonds.commit(half.data());
    CHECK(bonds.dissipated() == before);
  }
}

TEST_CASE("a crack through a lattice: its bonds hold G_f per unit area", "[models][cohesive]") {
  // Every bond crossing the plane x = mid (between two lattice planes) of a lattice large
  // enough that its middle is bulk, counted over the middle's cross-section only: spent, they
  // have dissipated sum F0 eta_u / 2. The mean over directions is what the law is scaled by;
  // along a lattice axis fewer bonds cross, by a few percent (measured 0.961 in 2-D, 0.982 in 3-D).
  // The peak traction is the bar's test (tests/cli/test_quasi_static_fracture.cpp).
  for (const int d : {2, 3}) {
    INFO("dim " << d);
    const int n = d == 2 ? 40 : 16;
    const double h = 1e-3;
    const Lattice l(d, n, h);
    const BondGraph graph(l.families);
    const double mid = 0.5 * n * h, lo = 4 * h, hi = (n - 4) * h;  // the bulk of the cross-section
    std::vector<std::pair<ParticleId, ParticleId>> crossing;
    for (const auto& [i, j] : all_pairs(l.families)) {
      const double* xi = &l.cloud.x[i * d];
      const double* xj = &l.cloud.x[j * d];
      if ((xi[0] - mid) * (xj[0] - mid) >= 0.0) continue;
      bool inside = true;  // the bond's first end within the bulk cross-section
      for (int a = 1; a < d; ++a) inside = inside && xi[a] > lo && xi[a] < hi;
      if (inside) crossing.emplace_back(i, j);
    }
    const double area = std::pow(hi - lo, d - 1);
    CohesiveBonds bonds(d, l.cloud.x, l.cloud.volume, graph, law);
    bonds.add(crossing);
    // Spent: the two halves pulled apart by 4 eta_u along x (a crossing bond has e_x >= 1 / 3.015).
    std::vector<double> u(l.cloud.size() * d, 0.0);
    for (std::size_t p = 0; p < l.cloud.size(); ++p) u[p * d] = l.cloud.x[p * d] > mid ? 4 * bonds.opening_limit() : 0.0;
    bonds.commit(u.data());
    CHECK(bonds.spent() == bonds.size());
    const double G = bonds.dissipated() / area;
    CHECK(G / law.G_f == Approx(1.0).margin(0.05));
    INFO("G / G_f " << G / law.G_f);
    CHECK(G > 0.0);
  }
}

TEST_CASE("an inclined crack's bonds hold G_f per unit area to the lattice's count in its direction", "[models][cohesive]") {
  // The plane's normal n = (1, 1) / sqrt 2 (2-D) or (1, 1, 0) / sqrt 2 (3-D), midway between
  // two of the lattice's diagonal planes (index sums k and k + 1); the crossing bonds whose end
  // on the near side lies in a window of the plane holding m particles of each diagonal line
  // (and, in 3-D, the layers 7..16 along z), with both ends' families whole. Spent, per unit
  // area they hold G_f sum_j |xi_j . n| / (c_d sum_j |xi_j|) over a whole family: the law is
  // scaled by the mean over directions, and each direction has its count. Measured 0.9813 in
  // 2-D and 0.9718 in 3-D (along the axes 0.961 and 0.982, the test above; 26.6 degrees in 2-D
  // 1.003 by the same count): within 4% of G_f whichever way a crack runs through the lattice.
  const double pi = 3.14159265358979323846, s = 1.0 / std::sqrt(2.0), h = 1e-3;
  for (const int d : {2, 3}) {
    INFO("dim " << d);
    const int n = 24, k = n - 1, m = 5;
    const Lattice l(d, n, h);
    auto index = [&](ParticleId p, int a) { return int(std::floor(l.cloud.x[p * d + a] / h)); };
    auto side = [&](ParticleId p) { return index(p, 0) + index(p, 1) - k - 0.5; };  // n . x, in h s
    auto in_window = [&](ParticleId p) {
      const int along = index(p, 1) - index(p, 0);  // t . x in h s, t = (-1, 1) / sqrt 2
      return along > -m && along <= m && (d == 2 || (index(p, 2) >= 7 && index(p, 2) <= 16));
    };
    std::vector<std::pair<ParticleId, ParticleId>> crossing;
    for (const auto& [i, j] : all_pairs(l.families)) {
      if (side(i) * side(j) >= 0.0) continue;
      if (in_window(side(i) < 0.0 ? i : j)) crossing.emplace_back(i, j);
    }
    const double area = 2 * m * h * s * (d == 3 ? 10 * h : 1.0);
    // Every end's family whole (indices 3..20 of 0..23 at 3.015 h), so S is the bulk's.
    bool whole = true;
    for (const auto& [i, j] : crossing)
      for (int a = 0; a < d; ++a)
        for (const ParticleId p : {i, j}) whole = whole && index(p, a) >= 3 && index(p, a) <= 20;
    REQUIRE(whole);
    REQUIRE(crossing.size() > 100);
    const BondGraph graph(l.families);
    CohesiveBonds bonds(d, l.cloud.x, l.cloud.volume, graph, law);
    bonds.add(crossing);
    // Spent: the far side moved by 10 eta_u along n (a crossing bond has |e . n| >= s / 3.015).
    std::vector<double> u(l.cloud.size() * d, 0.0);
    for (std::size_t p = 0; p < l.cloud.size(); ++p)
      if (side(ParticleId(p)) > 0.0)
        for (int a = 0; a < 2; ++a) u[p * d + a] = 10 * bonds.opening_limit() * s;
    bonds.commit(u.data());
    REQUIRE(bonds.spent() == bonds.size());
    // The count in this direction over the family of a particle in the middle.
    const ParticleId mid = ParticleId(std::size_t(n / 2) * (d == 3 ? n * n + n + 1 : n + 1));
    double across = 0.0, length = 0.0;
    for (Offset q = l.families.begin(mid); q < l.families.end(mid); ++q) {
      const ParticleId j = l.families.neighbors[q];
      double xn = 0.0, r2 = 0.0;
      for (int a = 0; a < d; ++a) {
        const double xi = l.cloud.x[j * d + a] - l.cloud.x[mid * d + a];
        r2 += xi * xi, xn += a < 2 ? xi * s : 0.0;
      }
      across += std::abs(xn), length += std::sqrt(r2);
    }
    const double c_d = d == 2 ? 2.0 / pi : 0.5, expected = across / (c_d * length);
    const double G = bonds.dissipated() / area;
    INFO("G / G_f " << G / law.G_f << ", the count " << expected);
    CHECK(G / law.G_f == Approx(expected).epsilon(1e-9));
    CHECK(expected == Approx(d == 2 ? 0.9813 : 0.9718).epsilon(1e-3));
  }
}

TEST_CASE("breaking at a state with softening bonds updates force and energy as if taken anew", "[models][cohesive]") {
  for (const int d : {2, 3}) {
    INFO("dim " << d);
    const Lattice l(d, d == 2 ? 10 : 6, 1e-3);
    LinearElastic m = test::elastic_material(d);
    m.E = law.E;
    CorrespondenceOptions o;
    o.formulation = Formulation::classical;
    CorrespondenceModel model(l.cloud, l.families, m, o);
    CorrespondenceModel anew(l.cloud, l.families, m, o);
    model.soften_broken_bonds(law);
    anew.soften_broken_bonds(law);
    const std::vector<test::Bond> breaks = test::random_bonds(l.families, l.cloud.size() / 4, 11);
    const auto u = test::random_field(model.dofs(), 1e-8, 13);
    std::vector<double> f(u.size()), g(u.size());
    model.internal_force(u.data(), f.data());
    const double e0 = model.energy(u.data());
    const BondBreaks b = model.break_bonds(breaks, u.data(), f.data());
    anew.break_bonds(breaks);
    REQUIRE(model.cohesive()->size() == breaks.size());
    anew.internal_force(u.data(), g.data());
    CHECK(test::relative_difference(f, g) <= 1e-12);
    CHECK(b.released == Approx(e0 - anew.energy(u.data())).epsilon(1e-9));
    // The stiffness bound of listed rows is the whole bound's there.
    std::vector<ParticleId> rows;
    for (const auto& [i, j] : breaks) rows.push_back(i), rows.push_back(j);
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    const std::vector<double> all = model.stiffness_row_sums(), some = model.stiffness_row_sums(rows);
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int a = 0; a < d; ++a) CHECK(some[r * d + a] == Approx(all[rows[r] * d + a]).epsilon(1e-12));
    // A rank's listed rows are not built for softening bonds: refused, not silently left out.
    CHECK_THROWS_AS(model.visit_tangent_rows(rows, [](std::size_t, const std::vector<ParticleId>&,
                                                      const std::vector<double>&) {}),
                    std::logic_error);
    CHECK_THROWS_AS(model.cut_bonds(breaks), std::logic_error);
  }
}

TEST_CASE("the tangent rows with softening bonds are the force's derivative on every branch", "[models][cohesive]") {
  // Openings up to about 2e-5 m against eta_e of 1e-7 to 3e-7 m and eta_u = 7.9e-5 m: the
  // bonds sit on the secant (below the committed kappa), the softening branch and closed;
  // central differences of 1e-11 m stay far from the kinks.
  for (const int d : {2, 3}) {
    INFO("dim " << d);
    const Lattice l(d, d == 2 ? 9 : 5, 1e-3);
    LinearElastic m = test::elastic_material(d);
    m.E = law.E;
    CorrespondenceOptions o;
    o.formulation = Formulation::classical;
    CorrespondenceModel model(l.cloud, l.families, m, o);
    model.soften_broken_bonds(law);
    model.break_bonds(test::random_bonds(l.families, l.cloud.size() / 2, 5));
    const std::size_t n = model.dofs();
    model.cohesive()->commit(test::random_field(n, 2e-5, 7).data());
    const auto u = test::random_field(n, 1e-5, 9);
    model.prepare_tangent(u.data());
    std::vector<double> K(n * n, 0.0);
    model.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
      for (std::size_t q = 0; q < cols.size(); ++q)
        for (int a = 0; a < d; ++a)
          for (int b = 0; b < d; ++b) K[(i * d + a) * n + cols[q] * d + b] += blocks[(q * d + a) * d + b];
    });
    const double h = 1e-11;
    double diff = 0.0, top = 0.0;
    std::vector<double> up(u), fp(n), fm(n);
    for (std::size_t c = 0; c < n; ++c) {
      up[c] = u[c] + h;
      model.internal_force(up.data(), fp.data());
      up[c] = u[c] - h;
      model.internal_force(up.data(), fm.data());
      up[c] = u[c];
      for (std::size_t r = 0; r < n; ++r) {
        const double fd = (fp[r] - fm[r]) / (2 * h);
        diff = std::max(diff, std::abs(fd - K[r * n + c]));
        top = std::max(top, std::abs(K[r * n + c]));
      }
    }
    CHECK(diff <= 1e-6 * top);
    // Leaving the softening bonds out would miss the differences' tolerance 100 times over.
    CorrespondenceModel plain(l.cloud, l.families, m, o);
    plain.break_bonds(test::random_bonds(l.families, l.cloud.size() / 2, 5));
    plain.prepare_tangent(u.data());
    double apart = 0.0;
    plain.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
      for (std::size_t q = 0; q < cols.size(); ++q)
        for (int a = 0; a < d; ++a)
          for (int b = 0; b < d; ++b)
            apart = std::max(apart, std::abs(K[(i * d + a) * n + cols[q] * d + b] - blocks[(q * d + a) * d + b]));
    });
    CHECK(apart > 100 * 1e-6 * top);
  }
}

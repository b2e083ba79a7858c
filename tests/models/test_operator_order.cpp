// model.operator_order: 2 (THEORY sec. 6): correspondence elasticity with G from the gradient
// weights of the second-order fit and the second-order operator energy as stabilization
// (seed 002 eq. 35-39). The same consistency tests as order 1 (force = dE/du, tangent =
// dF/du, ADR = Newton), the patch properties it must keep, the quadratic exactness it adds,
// and a measured comparison of both orders against the CalculiX reference of the demo.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>
#include <string>

#include "../support/adr_and_newton.hpp"
#include "../support/clouds.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/newton.hpp"

using namespace perinom;

namespace {

/// A 12 mm x 16 mm plane-strain block, bottom fixed, pressure on top and a shear traction on
/// the right, with the given formulation, jitter and operator order.
Problem block(const char* formulation, double jitter, int order = 2, double c_hg = 0.5, double ratio = 3.015) {
  std::ostringstream s;
  s << "name: block\ndimension: 2\n"
    << "geometry: {box: {min: [0, 0], max: [0.012, 0.016]}}\n"
    << "discretization: {dx: 0.001, horizon: {ratio: " << ratio << "}, jitter: " << jitter << ", seed: 4}\n"
    << "material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000, plane: strain}\n"
    << "model: {formulation: " << formulation << ", stabilization: " << c_hg << ", operator_order: " << order << "}\n"
    << "boundary:\n  - {region: bottom, fix: [x, y], at: face}\n  - {region: top, pressure: 2.0e5}\n"
    << "  - {region: right, traction: [3.0e4, 1.0e4]}\n";
  return build_problem(parse_scene(s.str(), "block"));
}

/// u = A x + b (linear) plus, with `quadratic`, 1/2 x^T Q_a x per component.
std::vector<double> field(const PointCloud& c, bool quadratic) {
  const double A[2][2] = {{1e-3, -4e-4}, {2.5e-4, -2e-3}};
  std::vector<double> u(c.size() * 2);
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double x = c.x[2 * i], y = c.x[2 * i + 1];
    u[2 * i] = 1e-6 + A[0][0] * x + A[0][1] * y + (quadratic ? 0.5 * x * x - 0.3 * x * y + 0.2 * y * y : 0.0);
    u[2 * i + 1] = -2e-6 + A[1][0] * x + A[1][1] * y + (quadratic ? -0.4 * x * x + 0.6 * x * y + 0.1 * y * y : 0.0);
  }
  return u;
}

}  // namespace

TEST_CASE("the second-order G is exact for quadratic displacements at every particle, boundary included",
          "[models][operator_order]") {
  Problem p = block("classical", 0.25);
  REQUIRE(p.as<CorrespondenceModel>().operator_order() == 2);
  const PointCloud& c = p.cloud;
  const std::vector<double> u = field(c, true);
  std::vector<double> H(c.size() * 4);
  p.as<CorrespondenceModel>().gradient(u.data(), H.data());
  double err = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double x = c.x[2 * i], y = c.x[2 * i + 1];
    const double exact[4] = {1e-3 + x - 0.3 * y, -4e-4 - 0.3 * x + 0.4 * y, 2.5e-4 - 0.8 * x + 0.6 * y,
                             -2e-3 + 0.6 * x + 0.2 * y};
    for (int k = 0; k < 4; ++k) err = std::max(err, std::abs(H[4 * i + k] - exact[k]));
  }
  CHECK(err < 1e-12);
  // The first-order G is not: its error at the boundary is O(dx) (about 1e-3 here).
  Problem q = block("classical", 0.25, 1);
  q.as<CorrespondenceModel>().gradient(u.data(), H.data());
  double err1 = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double x = c.x[2 * i], y = c.x[2 * i + 1];
    err1 = std::max(err1, std::abs(H[4 * i] - (1e-3 + x - 0.3 * y)));
  }
  CHECK(err1 > 1e-5);
}

TEST_CASE("order 2: no force for a linear displacement away from the surface, strong rows exact for uniform stress",
          "[models][operator_order]") {
  // The stabilization vanishes on quadratics, so only the stress term remains.
  SECTION("strong form on a jittered cloud: f_i = 0 inside, V_i P m_i on the surface") {
    Problem p = block("strong", 0.25);
    const std::vector<double> u = field(p.cloud, false);
    std::vector<double> f(u.size()), H(u.size() * 2), sigma;
    p.as<CorrespondenceModel>().internal_force(u.data(), f.data());
    p.as<CorrespondenceModel>().stress3(u.data(), sigma);
    const double scale = std::abs(sigma[0]) + std::abs(sigma[4]);
    const Surface& s = p.as<CorrespondenceModel>().surface();
    for (std::size_t i = 0; i < p.cloud.size(); ++i) {
      const double V = p.cloud.volume[i];
      const double* m = s.normal_over_h.data() + 2 * i;
      const double* sg = sigma.data() + 9 * i;
      for (int a = 0; a < 2; ++a) {
        const double expected = V * (sg[3 * a] * m[0] + sg[3 * a + 1] * m[1]);
        INFO("particle " << i << (s.on_surface[i] ? " (surface)" : ""));
        REQUIRE(std::abs(f[2 * i + a] - expected) <= 1e-9 * scale * V / 1e-3);
      }
    }
  }
  SECTION("classical form on a lattice: f_i = 0 two horizons from the boundary") {
    Problem p = block("classical", 0.0, 2, 0.5, 2.015);
    const std::vector<double> u = field(p.cloud, false);
    std::vector<double> f(u.size()), sigma;
    p.as<CorrespondenceModel>().internal_force(u.data(), f.data());
    p.as<CorrespondenceModel>().stress3(u.data(), sigma);
    const double scale = (std::abs(sigma[0]) + std::abs(sigma[4])) * 1e-6 / 1e-3;  // sigma V / dx
    const double reach = 2 * 2.015e-3;
    std::size_t inside = 0;
    for (std::size_t i = 0; i < p.cloud.size(); ++i) {
      const double x = p.cloud.x[2 * i], y = p.cloud.x[2 * i + 1];
      if (x < reach || x > 0.012 - reach || y < reach || y > 0.016 - reach) continue;
      ++inside;
      for (int a = 0; a < 2; ++a) REQUIRE(std::abs(f[2 * i + a]) <= 1e-9 * scale);
    }
    CHECK(inside > 0);
  }
}

TEST_CASE("order 2: the classical force is the derivative of the energy, stabilization included",
          "[models][operator_order]") {
  Problem p = block("classical", 0.25);
  REQUIRE(p.as<CorrespondenceModel>().stabilization()->stored() != nullptr);
  const std::size_t n = p.as<CorrespondenceModel>().dofs();
  const std::vector<double> u = test::random_field(n, 1e-5, 9);
  std::vector<double> f(n);
  p.as<CorrespondenceModel>().internal_force(u.data(), f.data());
  const double fmax = test::max_abs(f), h = 1e-9;
  for (const std::size_t k : {std::size_t(0), std::size_t(7), n / 2, n - 1}) {
    std::vector<double> up = u, um = u;
    up[k] += h, um[k] -= h;
    const double fd = (p.as<CorrespondenceModel>().energy(up.data()) - p.as<CorrespondenceModel>().energy(um.data())) / (2 * h);
    INFO("dof " << k);
    CHECK(std::abs(fd - f[k]) <= 1e-6 * fmax);
  }
}

TEST_CASE("order 2: the tangent rows are the derivative of the force", "[models][operator_order]") {
  for (const char* formulation : {"classical", "improved", "strong"})
    for (const double c_hg : {0.0, 0.5}) {
      Problem p = block(formulation, 0.25, 2, c_hg);
      const std::size_t n = p.as<CorrespondenceModel>().dofs();
      const std::vector<double> u = test::random_field(n, 1e-5, 1), v = test::random_field(n, 1e-5, 2);
      std::vector<double> fu(n), fuv(n), uv(u), Kv(n, 0.0);
      for (std::size_t k = 0; k < n; ++k) uv[k] += v[k];
      p.as<CorrespondenceModel>().internal_force(u.data(), fu.data());
      p.as<CorrespondenceModel>().internal_force(uv.data(), fuv.data());
      p.as<CorrespondenceModel>().visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& b) {
        for (std::size_t q = 0; q < cols.size(); ++q)
          for (int a = 0; a < 2; ++a)
            for (int c = 0; c < 2; ++c) Kv[2 * i + a] += b[(q * 2 + a) * 2 + c] * v[2 * cols[q] + c];
      });
      // Linear elasticity: the force is affine, so f(u + v) - f(u) = K v to rounding.
      double err = 0.0;
      for (std::size_t k = 0; k < n; ++k) err = std::max(err, std::abs(fuv[k] - fu[k] - Kv[k]));
      INFO(formulation << ", C_hg " << c_hg);
      CHECK(err <= 1e-9 * test::max_abs(Kv));
    }
}

namespace {

Problem demo(int order, const std::string& formulation) {
  return build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/uniaxial_compression.yaml",
                                  {"model.operator_order=" + std::to_string(order), "model.formulation=" + formulation}));
}

double top_centre_uy(Problem& p, const std::vector<double>& u) {
  std::vector<double> sigma, H(u.size() * 2);
  p.as<CorrespondenceModel>().stress3(u.data(), sigma);
  p.as<CorrespondenceModel>().gradient(u.data(), H.data());
  return point_probe_value(p.probes.at(0), {p.cloud, u, sigma, H});
}

}  // namespace

TEST_CASE("order 2: ADR and Newton agree on the demo scene", "[models][operator_order][newton]") {
  Problem p = demo(2, "improved");
  const auto r = test::adr_and_newton(p.as<CorrespondenceModel>(), p.loading);
  WARN("demo, operator order 2: ADR (tolerance 1e-11) and Newton differ by " << r.relative_l2 << " (relative L2)");
  CHECK(r.relative_l2 < 1e-6);
}

TEST_CASE("operator order 1 and 2 on the demo against the CalculiX reference", "[models][operator_order][verification]") {
  // The reference (verification/fem, Richardson-extrapolated): -0.4466475 mm top-centre u_y.
  // Measured (Newton, dx = 1 mm, support at the face; error = u_y / u_fem - 1): improved
  // +0.011% (order 1) and +0.006% (order 2); consistent +0.037% and +0.018%; classical +0.19%
  // and +0.41%. Classical's support at the face is in Galerkin form since the formulation issue
  // (the reaction spreads over the particles the face reconstruction reads), while its load
  // stays on the outer layer: that mismatch, not the gradient, dominates its error now, so the
  // second-order gradient no longer helps it (with the collocated support it went from -0.77%
  // to -0.056%).
  const double fem = -0.4466475e-3;
  for (const char* formulation : {"improved", "consistent", "classical"}) {
    double error[3] = {0.0, 0.0, 0.0};
    for (const int order : {1, 2}) {
      Problem p = demo(order, formulation);
      std::vector<double> u;
      REQUIRE(solve_newton(p.as<CorrespondenceModel>(), p.loading, NewtonOptions{}, u).converged);
      const double uy = top_centre_uy(p, u);
      error[order] = uy / fem - 1.0;
      WARN(formulation << ", operator order " << order << ": top_center_uy = " << uy << " m, error against FEM "
                       << error[order] * 100 << "%");
    }
    const double bound = std::string(formulation) == "classical" ? 0.006 : 0.001;
    CHECK(std::abs(error[1]) < bound);
    CHECK(std::abs(error[2]) < bound);
  }
}

TEST_CASE("order 2 in 3-D with k-nearest families: exact for quadratics, force = dE/du", "[models][operator_order]") {
  // Unequal supports: the transposed product runs over the dual-support.
  const std::string scene =
      "name: cube\ndimension: 3\ngeometry: {box: {min: [0, 0, 0], max: [0.006, 0.005, 0.004]}}\n"
      "discretization: {dx: 0.001, horizon: {neighbors: 30}, jitter: 0.2, seed: 3}\n"
      "material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000}\n"
      "model: {formulation: classical, stabilization: 0.5, operator_order: 2}\n"
      "boundary:\n  - {region: bottom, fix: [x, y, z]}\n";
  Problem p = build_problem(parse_scene(scene, "cube"));
  const PointCloud& c = p.cloud;
  const std::size_t n = p.as<CorrespondenceModel>().dofs();
  // u_a = x^T Q_a x / 2: grad u is Q_a x, exact for the second-order fit.
  std::vector<double> u(n), H(c.size() * 9);
  const double Q[3][3][3] = {{{0.5, 0.1, 0}, {0.1, -0.2, 0.3}, {0, 0.3, 0.4}},
                             {{-0.3, 0.2, 0.1}, {0.2, 0.6, 0}, {0.1, 0, -0.1}},
                             {{0.2, 0, -0.4}, {0, 0.1, 0.2}, {-0.4, 0.2, 0.3}}};
  for (std::size_t i = 0; i < c.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      double v = 0.0;
      for (int b = 0; b < 3; ++b)
        for (int e = 0; e < 3; ++e) v += 0.5 * c.x[3 * i + b] * Q[a][b][e] * c.x[3 * i + e];
      u[3 * i + a] = v;
    }
  p.as<CorrespondenceModel>().gradient(u.data(), H.data());
  double err = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        double exact = 0.0;
        for (int e = 0; e < 3; ++e) exact += Q[a][b][e] * c.x[3 * i + e];
        err = std::max(err, std::abs(H[9 * i + 3 * a + b] - exact));
      }
  CHECK(err < 1e-11);
  const std::vector<double> w = test::random_field(n, 1e-5, 5);
  std::vector<double> f(n);
  p.as<CorrespondenceModel>().internal_force(w.data(), f.data());
  const double fmax = test::max_abs(f), h = 1e-9;
  for (const std::size_t k : {std::size_t(1), n / 3, n - 2}) {
    std::vector<double> up = w, um = w;
    up[k] += h, um[k] -= h;
    const double fd = (p.as<CorrespondenceModel>().energy(up.data()) - p.as<CorrespondenceModel>().energy(um.data())) / (2 * h);
    INFO("dof " << k);
    CHECK(std::abs(fd - f[k]) <= 1e-6 * fmax);
  }
}

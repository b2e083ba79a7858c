#include <catch2/catch.hpp>

#include "../support/adr_and_newton.hpp"
#include "../support/clouds.hpp"
#include "../support/direct_solve.hpp"
#include "perinom/core/error.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/registry.hpp"
#include "perinom/solvers/jacobian.hpp"
#include "perinom/solvers/load_path.hpp"
#include "perinom/solvers/newton.hpp"

using namespace perinom;

namespace {

std::string plate(const char* formulation, const char* at, bool supported = true,
                  double stabilization = 0.5) {
  return std::string(R"(
name: plate
dimension: 2
geometry: {box: {min: [0, 0], max: [0.012, 0.024]}}
discretization: {dx: 0.001, horizon: {ratio: 3.015}, jitter: 0.2}
material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000, plane: strain}
model: {formulation: )") + formulation + ", stabilization: " + std::to_string(stabilization) + R"(}
boundary:
)" + (supported ? std::string("  - {region: bottom, fix: [x, y], at: ") + at + "}\n" : std::string()) + R"(  - {region: top, pressure: 2.0e5}
  - {region: right, traction: [3.0e4, 1.0e4]}
)";
}

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d / test::max_abs(b);
}

}  // namespace

const char* column_3d = R"(
name: column
dimension: 3
geometry: {box: {min: [0, 0, 0], max: [0.005, 0.005, 0.008]}}
discretization: {dx: 0.001, horizon: {ratio: 2.015}, jitter: 0.2}
material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000}
model: {formulation: improved, stabilization: 0.5}
boundary:
  - {region: bottom, fix: [x, y, z], at: face}
  - {region: top, pressure: 2.0e5}
)";

TEST_CASE("the assembled Jacobian is the derivative of the residual", "[solvers][newton]") {
  std::vector<std::string> scenes;
  for (const char* form : {"classical", "improved", "strong"})
    for (const char* at : {"layer", "face"})
      for (double c_hg : {0.0, 0.5}) scenes.push_back(plate(form, at, true, c_hg));
  scenes.push_back(column_3d);
  scenes.push_back(std::string(column_3d).replace(std::string(column_3d).find("improved"), 8, "classical"));
  for (const auto& scene : scenes) {
    {
      Problem p = build_problem(parse_scene(scene, "scene"));
      StaticSystem system(p.as<CorrespondenceModel>(), p.loading);
      system.assemble(nullptr);
      const CsrMatrix& J = system.jacobian();
      const auto u = test::random_field(system.dofs(), 1e-4, 1);
      const auto v = test::random_field(system.dofs(), 1e-4, 2);
      // The residual is affine in u, so R(u + v) - R(u) = J v up to rounding.
      std::vector<double> Ru(u.size()), Ruv(u.size()), uv(u), Jv(u.size(), 0.0);
      for (std::size_t k = 0; k < u.size(); ++k) uv[k] += v[k];
      system.residual(u.data(), 0.7, Ru.data());
      system.residual(uv.data(), 0.7, Ruv.data());
      for (std::int64_t r = 0; r < J.rows; ++r) {
        for (std::int64_t s = J.row_ptr[r]; s < J.row_ptr[r + 1]; ++s) Jv[r] += J.val[s] * v[J.col[s]];
        if (r > 0 && J.row_ptr[r] < J.row_ptr[r + 1]) REQUIRE(std::is_sorted(J.col.begin() + J.row_ptr[r], J.col.begin() + J.row_ptr[r + 1]));
      }
      double err = 0.0, scale = 0.0;
      for (std::size_t k = 0; k < u.size(); ++k) err = std::max(err, std::abs(Ruv[k] - Ru[k] - Jv[k])), scale = std::max(scale, std::abs(Jv[k]));
      INFO(scene);
      CHECK(err <= 1e-9 * scale);
    }
  }
}

TEST_CASE("Newton converges in one iteration on a linear problem, to the direct solution", "[solvers][newton]") {
  for (const char* form : {"classical", "improved"})
    for (const char* at : {"layer", "face"}) {
      Problem p = build_problem(parse_scene(plate(form, at), "plate"));
      std::vector<double> u;
      NewtonOptions opt;
      opt.line_search = false;
      const SolveReport rep = solve_newton(p.as<CorrespondenceModel>(), p.loading, opt, u);
      INFO(form << ", " << at << ": " << rep.failure);
      REQUIRE(rep.converged);
      CHECK(rep.iterations == 1);
      CHECK(rep.residual < 1e-10);
      CHECK(relative_difference(u, test::direct_solve(p.as<CorrespondenceModel>(), p.loading)) < 1e-9);
    }
}

TEST_CASE("load steps reuse the factorization and end at the same answer", "[solvers][newton]") {
  Problem p = build_problem(parse_scene(plate("improved", "face"), "plate"));
  std::vector<double> one, four;
  NewtonOptions opt;
  REQUIRE(solve_newton(p.as<CorrespondenceModel>(), p.loading, opt, one).converged);
  opt.load_steps = 4;
  const SolveReport rep = solve_newton(p.as<CorrespondenceModel>(), p.loading, opt, four);
  REQUIRE(rep.converged);
  CHECK(rep.history.rows() == 4);
  CHECK(rep.iterations == 4);
  CHECK(relative_difference(four, one) < 1e-9);
}

TEST_CASE("ADR and Newton agree on the demo scene at a tight ADR tolerance", "[solvers][newton]") {
  Problem p = build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/uniaxial_compression.yaml"));
  const auto r = test::adr_and_newton(p.as<CorrespondenceModel>(), p.loading);
  WARN("demo: ADR (tolerance 1e-11) and Newton differ by " << r.relative_l2 << " (relative L2)");
  CHECK(r.relative_l2 < 1e-6);
}

TEST_CASE("a body free to move rigidly is reported as a missing boundary condition", "[solvers][newton]") {
  Problem p = build_problem(parse_scene(plate("improved", "layer", false), "plate"));
  for (const char* solver : {"klu", "umfpack"}) {
    INFO(solver);
    std::vector<double> u;
    NewtonOptions opt;
    opt.linear_solver = solver;
    CHECK_THROWS_WITH(solve_newton(p.as<CorrespondenceModel>(), p.loading, opt, u),
                      Catch::Contains("singular") && Catch::Contains("boundary condition is probably missing") &&
                          Catch::Contains(std::string(solver) == "klu" ? "estimated from KLU's factors"
                                                                       : "estimated from UMFPACK's factors"));
  }
}

TEST_CASE("KLU and UMFPACK take the same Newton steps", "[solvers][newton]") {
  // Symmetric (classical), non-symmetric (improved: strong rows) and bordered (face supports'
  // multipliers) Jacobians: the same iterates to rounding, in the same number of steps.
  for (const char* form : {"classical", "improved"})
    for (const char* at : {"layer", "face"}) {
      INFO(form << ", " << at);
      Problem p = build_problem(parse_scene(plate(form, at), "plate"));
      std::vector<double> klu, umfpack;
      NewtonOptions opt;
      opt.load_steps = 2;
      opt.linear_solver = "klu";
      const SolveReport a = solve_newton(p.as<CorrespondenceModel>(), p.loading, opt, klu);
      opt.linear_solver = "umfpack";
      const SolveReport b = solve_newton(p.as<CorrespondenceModel>(), p.loading, opt, umfpack);
      REQUIRE(a.converged);
      REQUIRE(b.converged);
      CHECK(a.iterations == b.iterations);
      CHECK(relative_difference(umfpack, klu) < 1e-12);
    }
  // A plastic load path with non-associated flow (a non-symmetric consistent tangent): the
  // biaxial example's first 3 + 3 steps.
  const auto path = [](const std::string& solver) {
    Problem p = build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/biaxial_compression.yaml",
                                         {"stages.0.steps=3", "stages.1.steps=3", "solver.type=newton",
                                          "solver.linear_solver=" + solver}));
    REQUIRE(p.scene.plasticity->d0 < 1.0);
    std::vector<double> u;
    const SolveReport rep = solve_load_path(p.physics(), p.stages, load_path_options(p), u);
    INFO(solver << ": " << rep.failure);
    REQUIRE(rep.converged);
    return u;
  };
  CHECK(relative_difference(path("umfpack"), path("klu")) < 1e-10);
}

namespace {

/// The seed's square plate at 21 x 21 nodes (dx = 0.025 m) with the given support.
Problem plate_21(const char* support) {
  const std::string name = std::string("thin_plate_") + support + ".yaml";
  return build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/" + name, {"discretization.dx=0.025"}));
}

}  // namespace

TEST_CASE("the assembled plate Jacobian is the finite-difference derivative of the plate residual",
          "[solvers][newton][plate]") {
  for (const char* support : {"simply_supported", "clamped"}) {
    Problem p = plate_21(support);
    REQUIRE(dynamic_cast<const ThinPlateModel*>(p.model.get()) != nullptr);
    StaticSystem system(p.physics(), p.loading);
    system.assemble(nullptr);
    const CsrMatrix& J = system.jacobian();
    const std::size_t n = system.dofs();
    const auto w = test::random_field(n, 1e-4, 3);
    std::vector<double> Rp(n), Rm(n), wp(w), wm(w);
    double jmax = 0.0;
    for (const double v : J.val) jmax = std::max(jmax, std::abs(v));
    // Central differences column by column on a sample of columns (interior, edge, corner).
    const double h = 1e-6;
    for (const std::size_t c : {std::size_t(0), std::size_t(1), std::size_t(22), n / 2, n - 23, n - 1}) {
      wp = w, wm = w;
      wp[c] += h, wm[c] -= h;
      system.residual(wp.data(), 1.0, Rp.data());
      system.residual(wm.data(), 1.0, Rm.data());
      for (std::int64_t r = 0; r < J.rows; ++r) {
        double Jrc = 0.0;
        for (std::int64_t s = J.row_ptr[r]; s < J.row_ptr[r + 1]; ++s)
          if (J.col[s] == static_cast<std::int64_t>(c)) Jrc = J.val[s];
        INFO(support << ": row " << r << ", column " << c);
        REQUIRE(std::abs((Rp[r] - Rm[r]) / (2 * h) - Jrc) <= 1e-7 * jmax);
      }
    }
  }
}

TEST_CASE("Newton's plate deflection equals ADR's on the 21 x 21 simply supported and clamped plates",
          "[solvers][newton][plate]") {
  for (const char* support : {"simply_supported", "clamped"}) {
    Problem p = plate_21(support);
    REQUIRE(p.cloud.size() == 21 * 21);
    const auto r = test::adr_and_newton(p.physics(), p.loading);
    CHECK(r.newton_iterations == 1);  // the plate is linear
    WARN(support << " plate: ADR (tolerance 1e-11) and Newton differ by " << r.relative_l2 << " (relative L2)");
    CHECK(r.relative_l2 < 1e-6);
    CHECK(relative_difference(r.adr, r.newton) < 1e-6);
  }
}

TEST_CASE("Newton refuses a loading that does not fit the model, and zero load steps", "[solvers][newton]") {
  Problem p = build_problem(parse_scene(plate("classical", "layer"), "plate"));
  auto& model = p.as<CorrespondenceModel>();
  std::vector<double> u;
  Loading beyond = p.loading;
  beyond.fix(static_cast<std::int64_t>(model.dofs()), 0.0);
  REQUIRE_THROWS_WITH(solve_newton(model, beyond, {}, u), Catch::Contains("Loading::fixed["));
  NewtonOptions opt;
  opt.load_steps = 0;
  REQUIRE_THROWS_WITH(solve_newton(model, p.loading, opt, u), Catch::Contains("NewtonOptions::load_steps = 0"));
}

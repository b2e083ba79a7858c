// solver.type direct: one Cholesky factorization of the Galerkin-reduced stiffness gives
// Newton's answer on linear problems (plain and face-located constraints, prescribed
// displacements, orders 1 and 2, the thin plate), refuses what is not linear and
// symmetric, and keeps no overflowing answer.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <fstream>

#include "../support/cli.hpp"
#include "../support/clouds.hpp"
#include "../support/slurp.hpp"
#include "../support/pulled_bar.hpp"
#include "../support/small_plate.hpp"
#include "perinom/core/error.hpp"
#include "perinom/scene/registry.hpp"

using namespace perinom;

namespace {

std::vector<double> solve_with(const std::string& scene, const std::string& solver) {
  Problem p = build_problem(parse_scene(scene + "solver: {type: " + solver + "}\n", "direct.yaml"));
  std::vector<double> u(p.physics().dofs(), 0.0);
  const SolveReport rep = solve_problem(p, u);
  INFO(solver << ": " << rep.failure);
  REQUIRE(rep.converged);
  return u;
}

// A plane-strain block held at the left face (Galerkin form), its right face moved and its
// top pulled: face-located constraints with a prescribed value and a traction.
const std::string block = R"(
name: block
dimension: 2
geometry: {box: {min: [0, 0], max: [0.02, 0.01]}}
discretization: {dx: 0.001, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 2.0e11, nu: 0.3, density: 7800, plane: strain}
boundary:
  - {region: left, fix: [x, y], at: face}
  - {region: right, displacement: {x: 1.0e-6}, at: face}
  - {region: top, traction: [0, 2.0e6]}
)";


double relative(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) diff = std::max(diff, std::abs(a[k] - b[k]));
  return diff / test::max_abs(b);
}

}  // namespace

TEST_CASE("the direct solve gives Newton's answer on linear problems", "[solvers][direct]") {
  struct Case {
    std::string name, scene;
  };
  const Case cases[] = {
      {"pulled bar, plain constraints", test::pulled_bar},
      {"block, face constraints, consistent order 2", block},
      {"block, classical order 1", block + "model: {formulation: classical}\n"},
      {"thin plate", test::small_plate},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const std::vector<double> direct = solve_with(c.scene, "direct");
    const std::vector<double> newton = solve_with(c.scene, "newton");
    CHECK(relative(direct, newton) <= 1e-8);
  }
}

TEST_CASE("the direct solve refuses a plastic material, load stages and non-symmetric formulations",
          "[solvers][direct]") {
  auto message = [](const std::string& text) {
    try {
      parse_scene(text, "direct.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(message(block + "model: {formulation: improved}\nsolver: {type: direct}\n")
            .find("solver.type: direct needs a symmetric stiffness") != std::string::npos);
  const std::string plastic = R"(
name: dp
dimension: 2
geometry: {box: {min: [0, 0], max: [0.01, 0.01]}}
discretization: {dx: 0.001, horizon: {ratio: 3.015}}
material: {type: drucker_prager, E: 1.0e9, nu: 0.25, density: 1000, cohesion: 1.0e6, friction_angle: 30}
boundary:
  - {region: bottom, fix: [x, y]}
  - {region: top, pressure: 1.0e5}
solver: {type: direct}
)";
  CHECK(message(plastic).find("solver.type: direct solves a linear problem") != std::string::npos);
}

TEST_CASE("perinom run with solver.type direct writes a converged summary and its reactions", "[solvers][direct][cli]") {
  cli_test::ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << block + "solver: {type: direct}\n";
  const cli_test::Outcome o = cli_test::perinom(dir, "run scene.yaml --out out");
  INFO(o.err);
  REQUIRE(o.exit_code == 0);
  const std::string summary = test_support::slurp(dir.path / "out" / "summary.json");
  CHECK(summary.find("\"status\": \"converged\"") != std::string::npos);
  const std::string history = test_support::slurp(dir.path / "out" / "history.csv");
  CHECK(history.rfind("residual,boundary.0.Rx", 0) == 0);
}

TEST_CASE("a direct solve with a rigid mode left free stops with exit 3, naming the cause", "[solvers][direct][cli]") {
  // The pulled bar without its one y support: K_T is singular.
  const std::string free_bar = cli_test::with(test::pulled_bar, "  - {region: {box: {min: [0, 0], max: [0.002, 0.002]}}, fix: [y]}\n", "");
  cli_test::ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << free_bar + "solver: {type: direct}\n";
  const cli_test::Outcome o = cli_test::perinom(dir, "run scene.yaml --out out");
  CHECK(o.exit_code == 3);
  CHECK(o.err.find("not positive definite") != std::string::npos);
  CHECK(test_support::slurp(dir.path / "out" / "summary.json").find("\"status\": \"not_converged\"") != std::string::npos);
}

TEST_CASE("a direct solve whose deflection overflows is a diverged solve, exit 3, as by ADR or Newton",
          "[solvers][direct][cli][plate]") {
  // A plate 1e-100 m thick: D0 ~ 1e-290 N m, the deflection ~ 1e285 m, its sum of squares
  // infinite. It ended "converged", exit 0, with that deflection in the probe.
  const std::string thin = cli_test::with(test::small_plate, "thickness: 0.002", "thickness: 1.0e-100");
  cli_test::ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml")
      << thin + "solver: {type: direct}\nprobes:\n  - {name: mid, point: [0.05, 0.05], field: deflection}\n";
  const cli_test::Outcome o = cli_test::perinom(dir, "run scene.yaml --out out");
  INFO(o.out << o.err);
  CHECK(o.exit_code == 3);
  CHECK(o.err.find("direct: the displacement became NaN or Inf") != std::string::npos);
  const std::string summary = test_support::slurp(dir.path / "out" / "summary.json");
  CHECK(summary.find("\"status\": \"diverged\"") != std::string::npos);
  CHECK(summary.find("\"mid\": 0") != std::string::npos);  // the last good state: unloaded
  CHECK(summary.find("null") == std::string::npos);
}

TEST_CASE("the direct solve refines on its factor while the residual is above the tolerance, never making it worse",
          "[solvers][direct]") {
  // A nearly incompressible block (lambda / mu = 5,000): K_T's rounding is what refinement
  // corrects. With a tolerance of 0.5 the first solve is kept (one iteration); with one no
  // solve can meet, all three refinements are taken and the residual is no larger.
  const std::string soft = cli_test::with(block, "nu: 0.3", "nu: 0.4999");
  auto solve = [&](const std::string& tolerance) {
    Problem p = build_problem(parse_scene(soft + "solver: {type: direct, tolerance: " + tolerance + "}\n", "d.yaml"));
    std::vector<double> u(p.physics().dofs(), 0.0);
    return solve_problem(p, u);
  };
  const SolveReport once = solve("0.5"), all = solve("1.0e-300"), standard = solve("1.0e-8");
  CHECK(once.converged);
  CHECK(once.iterations == 1);
  CHECK_FALSE(all.converged);
  CHECK(all.iterations == 4);
  CHECK(all.residual <= once.residual);
  CHECK(all.failure.find("residual") != std::string::npos);
  INFO("first residual " << once.residual << ", refined " << all.residual);
  CHECK(standard.converged);
}

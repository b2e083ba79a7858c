// Newton through PETSc (solver.linear_solver mumps | gamg) against Newton with KLU: the same
// discrete problem, so the same answer within the solver tolerance, elastic and plastic.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "perinom/core/error.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/registry.hpp"
#include "perinom/solvers/load_path.hpp"
#include "perinom/solvers/newton.hpp"
#include "perinom/solvers/petsc.hpp"

using namespace perinom;

namespace {

/// A jittered 2-D plate, face-located supports (Galerkin form), pressure and shear; or its
/// 3-D column.
std::string elastic(int dim, const std::string& solver) {
  const std::string common = "model: {formulation: consistent}\nsolver: {type: newton, tolerance: 1.0e-11, linear_solver: " +
                             solver + "}\n";
  if (dim == 2)
    return R"(
name: plate
dimension: 2
geometry: {box: {min: [0, 0], max: [0.012, 0.024]}}
discretization: {dx: 0.001, horizon: {ratio: 3.015}, jitter: 0.2}
material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000, plane: strain}
boundary:
  - {region: bottom, fix: [x, y], at: face}
  - {region: top, pressure: 2.0e5}
  - {region: right, traction: [3.0e4, 1.0e4]}
)" + common;
  return R"(
name: column
dimension: 3
geometry: {box: {min: [0, 0, 0], max: [0.004, 0.004, 0.008]}}
discretization: {dx: 0.001, horizon: {ratio: 3.015}, jitter: 0.2}
material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000}
boundary:
  - {region: bottom, fix: [x, y, z], at: face}
  - {region: top, traction: [2.0e4, 0, -2.0e5]}
)" + common;
}

double max_relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) diff = std::max(diff, std::abs(a[k] - b[k])), scale = std::max(scale, std::abs(b[k]));
  return diff / scale;
}

std::vector<double> solve(const std::string& scene, SolveReport* report = nullptr) {
  Problem p = build_problem(parse_scene(scene, "scene"));
  std::vector<double> u;
  const SolveReport rep = solve_newton(p.physics(), p.loading, newton_options(p), u);
  INFO(rep.failure);
  REQUIRE(rep.converged);
  if (report) *report = rep;
  return u;
}

}  // namespace

TEST_CASE("Newton through PETSc equals Newton with KLU on elastic problems", "[solvers][newton][petsc]") {
  if (!petsc_available()) {
    CHECK_THROWS_AS(parse_scene(elastic(2, "mumps"), "scene"), InputError);
    return;
  }
  for (const int dim : {2, 3}) {
    INFO("dimension " << dim);
    const std::vector<double> klu = solve(elastic(dim, "klu"));
    for (const char* solver : {"mumps", "gamg"}) {
      INFO(solver);
      SolveReport rep;
      const std::vector<double> u = solve(elastic(dim, solver), &rep);
      CHECK(max_relative_difference(u, klu) < 1e-9);
      CHECK(rep.residual < 1e-10);
      // A linear problem: one Newton step, with a linear solve that went below the tolerance.
      CHECK(rep.iterations == 1);
      const auto column = std::find(rep.history.columns.begin(), rep.history.columns.end(), "linear_iterations");
      REQUIRE(column != rep.history.columns.end());
      const double linear = rep.history.values[column - rep.history.columns.begin()];
      CHECK(linear >= 1);
      if (std::string(solver) == "mumps") CHECK(linear == 1);
    }
  }
}

TEST_CASE("GAMG uses the rigid-body modes as its near-null space", "[solvers][newton][petsc]") {
  if (!petsc_available()) return;
  // The same solve with and without the positions the modes are built from: smoothed
  // aggregation with the modes needs fewer conjugate-gradient iterations.
  Problem p = build_problem(parse_scene(elastic(3, "gamg"), "scene"));
  const auto linear_iterations = [&](const NewtonOptions& o) {
    std::vector<double> u;
    const SolveReport rep = solve_newton(p.physics(), p.loading, o, u);
    REQUIRE(rep.converged);
    return rep.history.values[4];
  };
  NewtonOptions with = newton_options(p);
  REQUIRE(with.positions.size() == p.cloud.x.size());
  NewtonOptions without = with;
  without.positions.clear();
  const double a = linear_iterations(with), b = linear_iterations(without);
  INFO("with the modes " << a << ", without " << b);
  CHECK(a < b);
}

TEST_CASE("Newton through PETSc follows the plastic load path as KLU does", "[solvers][newton][petsc]") {
  if (!petsc_available()) return;
  // The biaxial example (Drucker-Prager, consistent formulation) over 4 + 4 load steps.
  const auto path = [](const std::string& solver) {
    Problem p = build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/biaxial_compression.yaml",
                                         {"stages.0.steps=4", "stages.1.steps=4", "solver.type=newton",
                                          "solver.linear_solver=" + solver}));
    std::vector<double> u;
    const SolveReport rep = solve_load_path(p.physics(), p.stages, load_path_options(p), u);
    INFO(solver << ": " << rep.failure);
    REQUIRE(rep.converged);
    return u;
  };
  const std::vector<double> klu = path("klu");
  for (const char* solver : {"mumps", "gamg"}) {
    INFO(solver);
    CHECK(max_relative_difference(path(solver), klu) < 1e-8);
  }
}

TEST_CASE("Newton through PETSc names a body free to move, never gives a result", "[solvers][newton][petsc]") {
  if (!petsc_available()) return;
  // Only loads: nothing stops the rigid motion. MUMPS names the singular stiffness (as KLU
  // does); GAMG's conjugate gradients fail, and the report says the linear solver did.
  for (const char* solver : {"mumps", "gamg"}) {
    INFO(solver);
    std::string scene = elastic(2, solver);
    scene.replace(scene.find("  - {region: bottom, fix: [x, y], at: face}\n"), 44, "");
    Problem p = build_problem(parse_scene(scene, "scene"));
    std::vector<double> u;
    if (std::string(solver) == "mumps") {
      CHECK_THROWS_WITH(solve_newton(p.physics(), p.loading, newton_options(p), u), Catch::Contains("singular"));
      continue;
    }
    const SolveReport rep = solve_newton(p.physics(), p.loading, newton_options(p), u);
    INFO(rep.failure);
    CHECK_FALSE(rep.converged);
    CHECK(rep.failure.find("linear solver") != std::string::npos);
    for (const double v : u) REQUIRE(std::isfinite(v));
  }
}

TEST_CASE("GAMG names a stiffness singular along a free translation even when conjugate gradients converge",
          "[solvers][newton][petsc]") {
  if (!petsc_available()) return;
  // A bar held along x only, pulled along x: the loads are orthogonal to the free y
  // translation, so conjugate gradients converged serially (an arbitrary y translation) and
  // stopped as indefinite over 2 ranks. The stiffness is asked instead.
  Problem p = build_problem(parse_scene(R"(
name: bar
dimension: 2
geometry: {box: {min: [0, 0], max: [0.04, 0.01]}, thickness: 0.01}
discretization: {dx: 0.001, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 70.0e9, nu: 0.3, density: 2700, plane: stress}
model: {formulation: consistent}
boundary:
  - {region: left, fix: [x]}
  - {region: right, traction: [1.0e6, 0]}
solver: {type: newton, linear_solver: gamg}
)", "scene"));
  std::vector<double> u;
  const SolveReport rep = solve_newton(p.physics(), p.loading, newton_options(p), u);
  INFO(rep.failure);
  CHECK_FALSE(rep.converged);
  CHECK(rep.failure.find("the linear solver gamg failed in load step 1: a singular stiffness") != std::string::npos);
  // The last good state: the unloaded body.
  for (const double v : u) CHECK(v == 0.0);
}

TEST_CASE("solver.linear_solver is read and refused where it cannot work", "[solvers][newton][scene]") {
  std::string scene = elastic(2, "lu");
  CHECK_THROWS_WITH(parse_scene(scene, "scene"), Catch::Contains("linear_solver") && Catch::Contains("klu, umfpack, mumps or gamg"));
  if (!petsc_available()) return;
  scene = elastic(2, "gamg");
  scene.replace(scene.find("consistent"), 10, "improved");
  CHECK_THROWS_WITH(parse_scene(scene, "scene"), Catch::Contains("linear_solver") && Catch::Contains("collocates"));
}

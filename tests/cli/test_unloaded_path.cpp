// A load path that ends at rest (loaded, held, released): its loads and reactions at the end
// are rounding (1e-20 N after 2e4 N). Measured over them, a converged path read "equilibrium
// error 1.000" (every solver), a Newton path reported "converged" with a residual of 1.36
// against its tolerance of 1e-10, and the Newton check said ADR's answer differed by 259%.
// Each is now taken over the largest the path carried, and says so.
#include "../support/cli.hpp"

using namespace cli_test;

namespace {

const std::string released = R"(name: released
dimension: 2
geometry: {box: {min: [0.0, 0.0], max: [0.1, 0.02]}}
discretization: {dx: 0.005, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0, plane: strain}
stages:
  - {name: pull, steps: 2, boundary: [{region: left, fix: [x, y], at: face}, {region: right, pressure: -1.0e6}]}
  - {name: hold, steps: 2, boundary: [{region: left, fix: [x, y], at: face}, {region: right, fix: [x], at: face}]}
  - {name: release, steps: 1, boundary: [{region: left, fix: [x, y], at: face}]}
probes: [{name: tip, point: [0.1, 0.01], field: displacement, component: x}]
solver: {type: lbc, tolerance: 1.0e-9, displacement_tolerance: 1.0e-9}
)";

Outcome run_released(const ScratchDir& dir, const std::string& sets) {
  std::ofstream(dir.path / "scene.yaml") << released;
  return perinom(dir, "run scene.yaml --out out " + sets);
}

}  // namespace

TEST_CASE("a path released to rest is in equilibrium over the reaction it carried", "[cli][load_path]") {
  for (const std::string solver : {"lbc", "newton"}) {
    DYNAMIC_SECTION("solver " << solver) {
      ScratchDir dir;
      const Outcome o = run_released(dir, "--set solver.type=" + solver);
      INFO("stdout: " << o.out << "\nstderr: " << o.err);
      REQUIRE(o.exit_code == 0);
      CHECK(o.out.find("/ largest reaction carried along the path = ") != std::string::npos);
      const std::string summary = slurp(dir.path / "out" / "summary.json");
      CHECK(json_number(summary, "error") < 1e-9);
      CHECK(json_number(summary, "scale") == Approx(2.0e4).epsilon(1e-6));  // 1 MPa on 0.02 m x 1 m
      // Newton's residual over the path's load: rounding, not 1.36.
      CHECK(json_number(summary, "residual") < 1e-9);
    }
  }
}

TEST_CASE("the Newton check of a path released to rest compares over the path", "[cli][load_path]") {
  ScratchDir dir;
  const Outcome o = run_released(dir, "--set solver.check=newton");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  REQUIRE(o.exit_code == 0);
  CHECK(o.out.find("over the largest along the path: the path ends at rest") != std::string::npos);
  const std::string summary = slurp(dir.path / "out" / "summary.json");
  CHECK(json_number(summary, "displacement_relative_l2") < 1e-8);
  CHECK(json_number(summary, "stress_relative_l2") < 1e-8);
  CHECK(summary.find("\"relative_to\": \"the largest along the path (the end is at rest)\"") != std::string::npos);
}

TEST_CASE("a path that ends loaded keeps its own measures", "[cli][load_path]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << released;
  const Outcome o = perinom(dir, "run scene.yaml --out out --set stages.2.steps=1 --set solver.check=newton "
                                 "--set \"stages.2.boundary=[{region: left, fix: [x, y], at: face}, {region: right, "
                                 "displacement: {x: 1.0e-5}, at: face}]\"");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  REQUIRE(o.exit_code == 0);
  CHECK(o.out.find("along the path") == std::string::npos);
}

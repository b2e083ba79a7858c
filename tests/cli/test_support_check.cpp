// The warning of a static run whose supports leave a rigid motion free, as a user meets it,
// on the vibrating bar of the examples (left end held, right end pulled) solved by ADR, and
// on the simply supported plate of the examples with one edge left supported, whose singular
// stiffness Newton names by a plate's supports, in a run or in its check. Each test runs
// the real binary in its own temporary folder.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>

#include "../support/bar_run.hpp"
#include "../support/cli.hpp"

using bar_test::bar;
using bar_test::Outcome;

TEST_CASE("a static run names the rigid motion its supports leave free, and only then", "[cli][supports]") {
  const std::string adr = "--set discretization.dx=0.002 --set solver.type=adr";
  const Outcome held = bar("supports_held", "run", adr + " --out out");
  INFO(held.out << held.err);
  CHECK(held.exit_code == 0);
  CHECK(held.out.find("rigid motion") == std::string::npos);
  // The left end held along the bar only: the bar can slide across it. The pull is along the
  // bar, so ADR still balances: the warning says what could go wrong, it does not stop the run.
  const Outcome slides = bar("supports_slide", "run", adr + " --out out --set 'boundary.0.fix=[x]'");
  INFO(slides.out << slides.err);
  CHECK(slides.exit_code == 0);
  CHECK(slides.out.find("perinom: warning: boundary: the supports leave the body 1 rigid motion(s) free: it can move "
                        "along (0, 1).") != std::string::npos);
  // summary.json lists what the terminal said.
  const std::string summary = cli_test::slurp(slides.dir / "out" / "summary.json");
  REQUIRE(summary.find("\"warnings\": [") != std::string::npos);
  CHECK(summary.find("\"boundary: the supports leave the body 1 rigid motion(s) free: it can move along (0, 1).",
                     summary.find("\"warnings\": [")) != std::string::npos);
  // Explicit dynamics may move freely: no warning.
  const Outcome flies = bar("supports_verlet", "run", "--set discretization.dx=0.002 --set solver.steps=10 --out out "
                            "--set 'boundary.0.fix=[x]'");
  INFO(flies.out << flies.err);
  CHECK(flies.exit_code == 0);
  CHECK(flies.out.find("rigid motion") == std::string::npos);
}

TEST_CASE("a plate supported along one edge only is told it can turn about that edge", "[cli][supports]") {
  // The left edge (x = 0) simply supported, the others free, under the example's pressure: no
  // balance exists (Newton fails; ADR ran 200,000 iterations to a residual of 0.8 before the
  // warning existed). The plate examples, all edges supported, are not warned.
  std::string scene = cli_test::slurp(PERINOM_SOURCE_DIR "/examples/thin_plate_simply_supported.yaml");
  for (const char* edge : {"right", "bottom", "top"})
    scene = cli_test::with(scene, "  - {region: " + std::string(edge) + ", support: simply_supported}\n", "");
  cli_test::ScratchDir d;
  std::ofstream(d.path / "scene.yaml") << scene;
  const cli_test::Outcome hinge = cli_test::perinom(d, "run scene.yaml --out out --set solver.type=newton");
  INFO(hinge.out << hinge.err);
  CHECK(hinge.exit_code != 0);
  CHECK(hinge.out.find("perinom: warning: boundary: the supports leave the plate 1 rigid motion(s) free: it can turn "
                       "about the axis along (0, 1, 0) through (0, ") != std::string::npos);
  for (const char* example : {"thin_plate_simply_supported", "thin_plate_clamped"}) {
    const cli_test::Outcome held = cli_test::perinom(
        d, std::string("run '" PERINOM_SOURCE_DIR "/examples/") + example + ".yaml' --out " + example + " --set solver.type=newton");
    INFO(held.out << held.err);
    CHECK(held.exit_code == 0);
    CHECK(held.out.find("rigid motion") == std::string::npos);
  }
}

namespace {

/// The simply supported plate of the examples with its left edge supported only.
std::string hinged_plate() {
  std::string scene = cli_test::slurp(PERINOM_SOURCE_DIR "/examples/thin_plate_simply_supported.yaml");
  for (const char* edge : {"right", "bottom", "top"})
    scene = cli_test::with(scene, "  - {region: " + std::string(edge) + ", support: simply_supported}\n", "");
  return scene;
}

}  // namespace

TEST_CASE("a singular plate stiffness names the supports a plate takes, not fix", "[cli][supports][plate]") {
  // It said "fix enough components to stop rigid translation and rotation", and fix is refused
  // on a plate.
  cli_test::ScratchDir d;
  std::ofstream(d.path / "scene.yaml") << hinged_plate();
  const cli_test::Outcome o = cli_test::perinom(d, "run scene.yaml --out out --set solver.type=newton");
  INFO(o.out << o.err);
  CHECK(o.exit_code == 2);
  CHECK(o.err.find("Newton: the stiffness is singular") != std::string::npos);
  CHECK(o.err.find("support: simply_supported or clamped") != std::string::npos);
  CHECK(o.err.find("its edges now: left simply supported, right free, bottom free, top free") != std::string::npos);
  CHECK(o.err.find("fix enough components") == std::string::npos);
}

TEST_CASE("a Newton check that meets a singular stiffness is recorded beside the solve it checked", "[cli][supports][plate]") {
  // ADR stops at its iteration limit (exit 1); the check's Newton then refused the singular
  // stiffness, which ended the run with exit 2 and a summary without the ADR solve or probes.
  cli_test::ScratchDir d;
  std::ofstream(d.path / "scene.yaml") << hinged_plate();
  const cli_test::Outcome o =
      cli_test::perinom(d, "run scene.yaml --out out --set solver.check=newton --set solver.max_iterations=2000");
  INFO(o.out << o.err);
  CHECK(o.exit_code == 1);
  CHECK(o.out.find("perinom: warning: solver.check: newton could not solve: Newton: the stiffness is singular") !=
        std::string::npos);
  const std::string summary = cli_test::slurp(d.path / "out" / "summary.json");
  CHECK(summary.find("\"status\": \"not_converged\"") != std::string::npos);
  CHECK(summary.find("\"type\": \"adr\"") != std::string::npos);
  CHECK(summary.find("\"iterations\": 2000") != std::string::npos);
  CHECK(summary.find("\"center_w\": ") != std::string::npos);
  CHECK(summary.find("\"newton_error\": \"Newton: the stiffness is singular") != std::string::npos);
}

TEST_CASE("a plate whose stable step is 0 is refused naming its thickness beside density and E", "[cli][plate][verlet]") {
  // A plate's mass (rho t) and stiffness (E t^3) scale with its thickness too.
  cli_test::ScratchDir d;
  const cli_test::Outcome o = cli_test::perinom(d, "run " PERINOM_SOURCE_DIR "/examples/thin_plate_clamped.yaml "
                                                   "--out out --set solver.type=verlet --set material.density=1e-300");
  INFO(o.out << o.err);
  CHECK(o.exit_code == 2);
  CHECK(o.err.find("material.density = 1e-300 kg/m^3 with material.E = 2.1e+11 Pa and geometry.thickness = 0.01 m "
                   "give no time step") != std::string::npos);
}

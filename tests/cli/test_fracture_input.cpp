// The fracture keys (damage, precracks, velocity) on bad input: exit code 2 and one line that
// names the key, as for every other key (test_bad_input.cpp); and a valid fracture scene.
#include "../support/cli.hpp"

using namespace cli_test;

namespace {

// The tiny scene as a fracture run: classical formulation, Verlet, the top pulled at 1 m/s, a
// precrack from the left edge to the centre between two particle rows.
std::string fracture_scene() {
  return with(with(tiny_scene, "  - region: top\n    pressure: 1.0e6\n", "  - region: top\n    velocity: {y: 1.0}\n"),
         "solver:\n  type: adr\n  tolerance: 1.0e-6\n  displacement_tolerance: 1.0e-6\n",
         "model: {formulation: classical}\nsolver: {type: verlet, steps: 20}\n"
         "damage: {criterion: instability, s_max: 0.02}\n"
         "precracks:\n  - {from: [-0.0005, 0.005], to: [0.005, 0.005]}\n");
}

}  // namespace

TEST_CASE("the fracture scene used below is valid and runs", "[cli][fracture]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << fracture_scene();
  const Outcome o = perinom(dir, "run scene.yaml --out out");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  CHECK(o.exit_code == 0);
  std::ifstream history(dir.path / "out" / "history.csv");
  std::string header;
  std::getline(history, header);
  CHECK(header.find("broken_bonds,released_energy") != std::string::npos);
  // perinom check names what the precrack cut (10 particles a side: the two rows next to its
  // line lose their bonds across it, none loses its family).
  const Outcome c = perinom(dir, "check scene.yaml");
  INFO(c.out);
  CHECK(c.exit_code == 0);
  CHECK(c.out.find("bonds broken, 0 particle(s) detached") != std::string::npos);
}

TEST_CASE("the stretch criterion's s_c from G_c is printed by check and written to summary.json", "[cli][fracture]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml")
      << with(fracture_scene(), "criterion: instability, s_max: 0.02", "criterion: stretch, G_c: 2700.0");
  const Outcome c = perinom(dir, "check scene.yaml");
  INFO(c.out << c.err);
  REQUIRE(c.exit_code == 0);
  const auto at = c.out.find("damage          stretch, s_c = ");
  REQUIRE(at != std::string::npos);
  CHECK(c.out.find("from G_c = 2700 J/m^2 (bond-based calibration by the bulk modulus, inverse_square influence",
                   at) != std::string::npos);
  const double s_c = std::stod(c.out.substr(at + 31));
  const Outcome r = perinom(dir, "run scene.yaml --out out");
  REQUIRE(r.exit_code == 0);
  std::ifstream in(dir.path / "out" / "summary.json");
  const std::string summary((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto k = summary.find("\"s_c\": ");
  REQUIRE(k != std::string::npos);
  CHECK(std::stod(summary.substr(k + 7)) == Approx(s_c).epsilon(1e-3));
}

TEST_CASE("a damage criterion and its parameter are checked by key", "[cli][fracture]") {
  SECTION("unknown criterion") {
    const std::string s = with(fracture_scene(), "criterion: instability", "criterion: brittle");
    require_rejected(s, {"damage.criterion: must be instability, stretch or stress"});
  }
  SECTION("s_max not positive") {
    const std::string s = with(fracture_scene(), "s_max: 0.02", "s_max: 0");
    require_rejected(s, {"damage.s_max: must be positive"});
  }
  SECTION("the stretch criterion needs one of s_c and G_c") {
    const std::string s = with(fracture_scene(), "criterion: instability, s_max: 0.02", "criterion: stretch");
    require_rejected(s, {"damage.criterion: stretch needs exactly one of s_c and G_c"});
    const std::string both = with(fracture_scene(), "criterion: instability, s_max: 0.02",
                                  "criterion: stretch, s_c: 0.01, G_c: 1000.0");
    require_rejected(both, {"damage.criterion: stretch needs exactly one of s_c and G_c"});
  }
  SECTION("G_c not positive") {
    const std::string s = with(fracture_scene(), "criterion: instability, s_max: 0.02", "criterion: stretch, G_c: 0");
    require_rejected(s, {"damage.G_c: must be positive"});
  }
  SECTION("every below 1") {
    const std::string s = with(fracture_scene(), "s_max: 0.02}", "s_max: 0.02, every: 0}");
    require_rejected(s, {"damage.every: must be at least 1"});
  }
  SECTION("another criterion's key is said to be one, not unknown") {
    const std::string s = with(fracture_scene(), "s_max: 0.02}", "s_max: 0.02, f_t: 1.0e6}");
    require_rejected(s, {"damage.f_t: belongs to criterion: stress, not instability"});
  }
}

TEST_CASE("damage needs Verlet or a load path, and the classical formulation", "[cli][fracture]") {
  SECTION("a static solver") {
    const std::string s = with(with(fracture_scene(), "type: verlet, steps: 20", "type: adr"), "velocity: {y: 1.0}",
                               "displacement: {y: 1.0e-5}");
    require_rejected(s, {"damage: bonds break during a Verlet run (solver.type verlet) or on a load path (stages, "
                         "solved by adr or lbc), not with solver.type adr without stages"});
  }
  SECTION("a load path checks after every balance") {
    const std::string s = with(slurp(PERINOM_SOURCE_DIR "/examples/brittle_bar.yaml"), "  f_t: 1.0e6\n", "  f_t: 1.0e6\n  every: 2\n");
    require_rejected(s, {"damage.every: applies to Verlet steps; a load path looks for bonds to break after every balance"});
  }
  SECTION("the Newton check of a plastic body, whose path depends on when bonds broke") {
    const std::string s = with(with(with(slurp(PERINOM_SOURCE_DIR "/examples/brittle_bar.yaml"),
                                         "material: {type: linear_elastic,",
                                         "material: {type: drucker_prager, friction_angle: 30.0, cohesion: 1.0e6,"),
                                    "plane: stress}", "plane: strain}"),
                               "solver: {type: adr,", "solver: {type: lbc, check: newton,");
    require_rejected(s, {"damage: solver.check: newton with drucker_prager and breaking bonds is not built"});
  }
  SECTION("the consistent formulation") {
    const std::string s = with(fracture_scene(), "formulation: classical", "formulation: consistent");
    require_rejected(s, {"damage: needs model.formulation classical (here consistent)"});
  }
}

TEST_CASE("a precrack of zero length and a velocity off Verlet or at a face are refused by key", "[cli][fracture]") {
  SECTION("zero length") {
    const std::string s = with(fracture_scene(), "to: [0.005, 0.005]", "to: [-0.0005, 0.005]");
    require_rejected(s, {"precracks[0].to: must differ from `from`"});
  }
  SECTION("velocity with ADR") {
    const std::string s = with(with(with(fracture_scene(), "type: verlet, steps: 20", "type: adr"),
                                    "damage: {criterion: instability, s_max: 0.02}\n", ""),
                               "precracks:\n  - {from: [-0.0005, 0.005], to: [0.005, 0.005]}\n", "");
    require_rejected(s, {"boundary[1].velocity: a prescribed velocity needs solver.type verlet"});
  }
  SECTION("velocity at a face") {
    const std::string s = with(fracture_scene(), "    velocity: {y: 1.0}\n", "    velocity: {y: 1.0}\n    at: face\n");
    require_rejected(s, {"boundary[1].velocity: is prescribed at the particles"});
  }
  SECTION("velocity and displacement on one component") {
    const std::string s = with(fracture_scene(), "    velocity: {y: 1.0}\n", "    velocity: {y: 1.0}\n    displacement: {y: 0.0}\n");
    require_rejected(s, {"boundary[1].velocity: prescribes the same component as displacement"});
  }
}

TEST_CASE("a precrack that cuts no bond is refused by its index, also beside one that cuts bonds", "[cli][fracture]") {
  // The check was on all the cracks together: a second crack off the body was ignored, exit 0.
  const std::string crack = "  - {from: [-0.0005, 0.005], to: [0.005, 0.005]}\n";
  const std::string s = with(fracture_scene(), crack, crack + "  - {from: [0.02, 0.02], to: [0.03, 0.02]}\n");
  require_rejected(s, {"precracks[1] cuts no bond"});
}

TEST_CASE("damage.every beyond solver.steps is warned: no step looks for bonds to break", "[cli][fracture]") {
  // It broke nothing and said nothing.
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml")
      << with(fracture_scene(), "s_max: 0.02}", "s_max: 0.02, every: 50}");
  const Outcome o = perinom(dir, "run scene.yaml --out out");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  CHECK(o.exit_code == 0);
  CHECK(o.out.find("perinom: warning: damage.every = 50 is beyond solver.steps = 20") != std::string::npos);
  const Outcome within = perinom(dir, "run scene.yaml --out within --set damage.every=20");
  CHECK(within.exit_code == 0);
  CHECK(within.out.find("damage.every") == std::string::npos);
}

TEST_CASE("a run without damage names the particles its precracks detached, as one with damage does", "[cli][fracture]") {
  // Two cracks around the corner particle cut all its bonds; only check said so before.
  const std::string corner = "  - {from: [-0.001, 0.001], to: [0.001, 0.001]}\n  - {from: [0.001, -0.001], to: [0.001, 0.001]}\n";
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml")
      << with(with(fracture_scene(), "damage: {criterion: instability, s_max: 0.02}\n", ""),
              "  - {from: [-0.0005, 0.005], to: [0.005, 0.005]}\n", corner);
  const Outcome o = perinom(dir, "run scene.yaml --out out");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  REQUIRE(o.exit_code == 0);
  CHECK(o.out.find("perinom: note: 1 particle(s) lost a family that spans the plane and were detached") != std::string::npos);
  CHECK(json_number(slurp(dir.path / "out" / "summary.json"), "detached_particles") == 1.0);
}

TEST_CASE("a no-fail zone that holds no particle is refused before the run, not ignored", "[cli][fracture]") {
  const std::string zone = "damage: {criterion: instability, s_max: 0.02, no_fail: [{region: ";
  SECTION("an inverted box") {
    const std::string s = with(fracture_scene(), "damage: {criterion: instability, s_max: 0.02}",
                               zone + "{box: {min: [0.01, 0.01], max: [0.0, 0.0]}}}]}");
    require_rejected(s, {at_line(s, "no_fail", "damage.no_fail[0].region: selects no particle")});
  }
  SECTION("a point off the body") {
    const std::string s = with(fracture_scene(), "damage: {criterion: instability, s_max: 0.02}",
                               zone + "{point: [5.0, 5.0]}}]}");
    require_rejected(s, {"damage.no_fail[0].region.point: the point is", "outside the body"});
  }
}

TEST_CASE("a Verlet run whose energy balance ends beyond 1% says so, and one within it does not", "[cli][fracture]") {
  // The coarse SENT without stabilization: zero-energy modes grow as bonds break, 2.6% off;
  // with C_hg = 0.5, 0.2%.
  ScratchDir dir;
  const std::string scene = std::string(PERINOM_SOURCE_DIR) + "/examples/sent.yaml";
  const Outcome bad = perinom(dir, "run " + scene + " --out bad --set model.stabilization=0 --set output.vtk_every=0");
  INFO(bad.out << bad.err);
  CHECK(bad.exit_code == 0);
  CHECK(bad.out.find("perinom: warning: the energy balance ends off by") != std::string::npos);
  const Outcome good = perinom(dir, "run " + scene + " --out good --set output.vtk_every=0");
  CHECK(good.exit_code == 0);
  CHECK(good.out.find("energy balance ends off") == std::string::npos);
  std::ifstream in(dir.path / "good" / "summary.json");
  const std::string summary((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto k = summary.find("\"energy_balance\": ");
  REQUIRE(k != std::string::npos);
  CHECK(std::stod(summary.substr(k + 18)) < 0.01);
}

TEST_CASE("damage.fracture_energy is checked by key, and refused where softening bonds are not built", "[cli][fracture]") {
  const std::string bar = slurp(PERINOM_SOURCE_DIR "/examples/brittle_bar.yaml");
  const auto soft = [&](const std::string& more) { return with(bar, "  f_t: 1.0e6\n", "  f_t: 1.0e6\n  fracture_energy: 50.0\n" + more); };
  SECTION("not positive") {
    require_rejected(with(bar, "  f_t: 1.0e6\n", "  f_t: 1.0e6\n  fracture_energy: 0\n"), {"damage.fracture_energy: must be positive"});
  }
  SECTION("below the elastic rise of the longest bond: the law would have no softening branch") {
    require_rejected(with(bar, "  f_t: 1.0e6\n", "  f_t: 1.0e6\n  fracture_energy: 1.0e-4\n"),
                     {"damage.fracture_energy: 0.0001 J/m^2 is below"});
  }
  SECTION("another criterion") {
    const std::string s = with(fracture_scene(), "s_max: 0.02}", "s_max: 0.02, fracture_energy: 50.0}");
    require_rejected(s, {"damage.fracture_energy: softens the bonds the stress criterion breaks (criterion: stress)"});
  }
  SECTION("Verlet") {
    const std::string s = with(fracture_scene(), "criterion: instability, s_max: 0.02",
                               "criterion: stress, f_t: 1.0e6, fracture_energy: 50.0");
    require_rejected(s, {"damage.fracture_energy: softening bonds in a Verlet run"});
  }
}

TEST_CASE("a 3-D precrack names the edge that is zero or parallel", "[cli][fracture]") {
  // A zero edge1 was reported as edge2 ("the two edges must span a rectangle").
  const std::string beam = slurp(PERINOM_SOURCE_DIR "/verification/fracture/four_point_beam_3d.yaml");
  const std::string edges = "edge1: [0.022, 0.022, 0.0], edge2: [0.0, 0.0, 0.0345]";
  require_rejected(with(beam, edges, "edge1: [0.0, 0.0, 0.0], edge2: [0.0, 0.0, 0.0345]"),
                   {"precracks[0].edge1: must be nonzero"});
  require_rejected(with(beam, edges, "edge1: [0.022, 0.022, 0.0], edge2: [0.0, 0.0, 0.0]"),
                   {"precracks[0].edge2: must be nonzero"});
  require_rejected(with(beam, edges, "edge1: [0.022, 0.022, 0.0], edge2: [0.011, 0.011, 0.0]"),
                   {"precracks[0].edge2: is parallel to edge1"});
}

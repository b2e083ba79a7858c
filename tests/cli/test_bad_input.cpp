// The perinom program on malformed input: every case must end with exit code 2 and one
// line on stderr that names the key (and its line, where YAML gives one) or the particle.
// Each test writes a tiny scene (10 x 10 particles) into its own temporary folder and
// runs the real binary (PERINOM_EXE, set by tests/CMakeLists.txt), so the whole file takes
// well under a second per case.
#include "../support/cli.hpp"

using namespace cli_test;

TEST_CASE("the tiny scene used below is valid", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  const Outcome o = perinom(dir, "check scene.yaml");
  INFO("stderr: " << o.err);
  CHECK(o.exit_code == 0);
  CHECK(o.err.empty());
  // check says where a point probe's value comes from: the top face's centre lies between
  // two particles, and the lower-numbered is read.
  INFO(o.out);
  CHECK(o.out.find("probe top_uy               point, particle 94 at (0.0045, 0.0095), 0.000707 m from the point: "
                   "its value is read at the particle") != std::string::npos);
}

TEST_CASE("an unknown top-level key is named with its line", "[cli]") {
  const std::string s = with(tiny_scene, "dimension: 2\n", "dimension: 2\ncolour: red\n");
  require_rejected(s, {at_line(s, "colour:", "colour: unknown key")});
}

TEST_CASE("an unknown nested key is named by its dotted path and line", "[cli]") {
  const std::string s = with(tiny_scene, "  E: 1.0e9\n", "  E: 1.0e9\n  Young: 2.0e9\n");
  require_rejected(s, {at_line(s, "Young:", "material.Young: unknown key")});
}

TEST_CASE("an unknown key in a list item is named with the item's index", "[cli]") {
  const std::string s = with(tiny_scene, "    fix: [x, y]\n", "    fix: [x, y]\n    colour: red\n");
  require_rejected(s, {at_line(s, "colour:", "boundary[0].colour: unknown key")});
}

TEST_CASE("a number given as text is a wrong type", "[cli]") {
  const std::string s = with(tiny_scene, "E: 1.0e9", "E: \"abc\"");
  require_rejected(s, {at_line(s, "E: \"abc\"", "material.E: must be a number")});
}

TEST_CASE("a scalar where a mapping belongs is a wrong type", "[cli]") {
  const std::string s = with(tiny_scene, "horizon: {ratio: 3.015}", "horizon: 3.015");
  require_rejected(s, {at_line(s, "horizon:", "discretization.horizon: must be a mapping")});
}

TEST_CASE("a missing required key is named", "[cli]") {
  const std::string s = with(tiny_scene, "  E: 1.0e9\n", "");
  // The line given is that of the enclosing mapping (its first key).
  require_rejected(s, {at_line(s, "  type: linear_elastic", "material.E: required key is missing")});
}

TEST_CASE("a non-positive Young's modulus is rejected", "[cli]") {
  for (const std::string e : {"0", "-1.0e9"}) {
    DYNAMIC_SECTION("E = " << e) {
      const std::string s = with(tiny_scene, "E: 1.0e9", "E: " + e);
      require_rejected(s, {at_line(s, "E: ", "material.E: must be positive")});
    }
  }
}

TEST_CASE("a non-positive particle spacing is rejected", "[cli]") {
  for (const std::string dx : {"0", "-0.001"}) {
    DYNAMIC_SECTION("dx = " << dx) {
      const std::string s = with(tiny_scene, "dx: 0.001", "dx: " + dx);
      require_rejected(s, {at_line(s, "dx:", "discretization.dx: must be positive")});
    }
  }
}

TEST_CASE("a non-positive density is rejected", "[cli]") {
  const std::string s = with(tiny_scene, "density: 1000.0", "density: 0");
  require_rejected(s, {at_line(s, "density:", "material.density: must be positive")});
}

TEST_CASE("Poisson's ratio outside (-1, 0.5) is rejected", "[cli]") {
  for (const std::string nu : {"0.5", "-1"}) {
    DYNAMIC_SECTION("nu = " << nu) {
      const std::string s = with(tiny_scene, "nu: 0.25", "nu: " + nu);
      require_rejected(s, {at_line(s, "nu:", "material.nu: must lie in (-1, 0.5)")});
    }
  }
}

TEST_CASE("a horizon too small for an invertible shape tensor names a particle", "[cli]") {
  const std::string s = with(tiny_scene, "ratio: 3.015", "ratio: 0.9");
  require_rejected(s, {"particle 0 at (", "shape tensor is singular",
                       "discretization.horizon.ratio"});
}

TEST_CASE("an empty geometry (max <= min) is rejected", "[cli]") {
  for (const std::string max : {"[0.01, 0.0]", "[-0.01, 0.01]"}) {
    DYNAMIC_SECTION("max = " << max) {
      const std::string s = with(tiny_scene, "max: [0.01, 0.01]", "max: " + max);
      require_rejected(s, {at_line(s, "box:", "geometry.box: max must exceed min")});
    }
  }
}

TEST_CASE("a region that selects no particle is named", "[cli]") {
  const std::string s = with(tiny_scene, "  - region: bottom\n",
                             "  - region: {box: {min: [1.0, 1.0], max: [2.0, 2.0]}}\n");
  require_rejected(s, {"scene.yaml", "boundary[0].region: selects no particle"});
}

TEST_CASE("a number out of a double's range is named as such", "[cli]") {
  // (1e400 was "must be a number", and in a list "must be a list of 2 numbers".)
  require_rejected(with(tiny_scene, "E: 1.0e9", "E: 1.0e400"), {"material.E: '1.0e400' is out of the range of a double"});
}

TEST_CASE("a number out of a double's range inside a list is named as such", "[cli]") {
  require_rejected(with(tiny_scene, "    pressure: 1.0e6\n", "    traction: [1e400, 0]\n"),
                   {"boundary[1].traction: '1e400' is out of the range of a double"});
}

TEST_CASE("a fix that names a component twice is refused", "[cli]") {
  // (It ran, holding x alone: the second name was a typo for another.)
  require_rejected(with(tiny_scene, "fix: [x, y]", "fix: [x, x]"), {"boundary[0].fix: names x twice"});
}

TEST_CASE("a fix that names no component is refused", "[cli]") {
  // (It ran, holding nothing, and was reported as a support with a reaction of zero.)
  require_rejected(with(tiny_scene, "fix: [x, y]", "fix: []"), {"boundary[0].fix: names no component"});
}

TEST_CASE("an unknown side name is named with its line", "[cli]") {
  const std::string s = with(tiny_scene, "region: top", "region: roof");
  require_rejected(s, {at_line(s, "roof", "boundary[1].region: unknown side 'roof'")});
}

TEST_CASE("an unknown formulation is refused with the known ones", "[cli]") {
  const std::string s = with(tiny_scene, "boundary:\n", "model: {formulation: improvd}\nboundary:\n");
  require_rejected(s, {at_line(s, "model:", "model.formulation:"), "classical, improved or strong"});
}

TEST_CASE("a face-located condition needs a side of the box", "[cli]") {
  const std::string s = with(tiny_scene, "  - region: bottom\n    fix: [x, y]\n",
                             "  - region: {box: {min: [0, 0], max: [0.01, 0.001]}}\n    fix: [x, y]\n    at: face\n");
  require_rejected(s, {"boundary[0].at", "side region"});
}

TEST_CASE("invalid YAML syntax gives the line of the error", "[cli]") {
  const std::string s = with(tiny_scene, "E: 1.0e9", "E: 1.0e9: 2");
  require_rejected(s, {at_line(s, "E: 1.0e9: 2", "not valid YAML")});
}

namespace {

/// tiny_scene with a hole of radius 1.5 spacings: its centre is within two spacings of the
/// edge particles, which the check for a point off the body lets pass.
std::string holed() {
  return with(tiny_scene, "max: [0.01, 0.01]}", "max: [0.01, 0.01]}\n  holes: [{center: [0.005, 0.005], radius: 0.0015}]");
}

}  // namespace

TEST_CASE("a point probe inside a small hole is an error, not the edge particle read", "[cli]") {
  require_rejected(holed(), {"probes[0].point: probe 'top_uy' lies inside hole 0 (centre (0.005, 0.005), radius 0.0015 m)"},
                   "--set probes[0].point=[0.005,0.005]");
}

TEST_CASE("a point region inside a small hole is an error, not the edge particle held", "[cli]") {
  require_rejected(with(holed(), "region: bottom", "region: {point: [0.0051, 0.0049]}"),
                   {"boundary[0].region.point: the point lies inside hole 0"});
}

TEST_CASE("a point probe on a hole's edge is on the body", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "edge.yaml") << holed();
  const Outcome edge = perinom(dir, "check edge.yaml --set probes[0].point=[0.005,0.0065]");
  INFO(edge.out << edge.err);
  CHECK(edge.exit_code == 0);
}

TEST_CASE("a point region outside the body is an error, not the nearest corner held", "[cli]") {
  const std::string s = with(tiny_scene, "region: bottom", "region: {point: [0.005, 0.015]}");
  require_rejected(s, {"boundary[0].region.point: the point is 0.0055", "particle 94 at (0.0045, 0.0095)", "outside the body"});
}

TEST_CASE("snapshots by load step on a scene without a load path are refused", "[cli]") {
  require_rejected(tiny_scene, {"output.vtk_steps: counts load steps, and this scene has none"},
                   "--set output.vtk_steps=[3]");
}

TEST_CASE("a hole that removes no particle is refused: the body would run without it", "[cli]") {
  const std::string box = "box: {min: [0.0, 0.0], max: [0.01, 0.01]}";
  SECTION("a centre in millimetres in a box in metres") {
    const std::string s = with(tiny_scene, box, box + "\n  holes: [{shape: circle, center: [5.0, 5.0], radius: 0.002}]");
    require_rejected(s, {"geometry: holes[0]: removes no particle", "radius 0.002 m, spacing 0.001 m"});
  }
  SECTION("a hole finer than the spacing, between particles") {
    const std::string s = with(tiny_scene, box, box + "\n  holes: [{shape: circle, center: [0.005, 0.005], radius: 0.0004}]");
    require_rejected(s, {"geometry: holes[0]: removes no particle"});
  }
}

TEST_CASE("a --set to an unknown key is named like a key in the file", "[cli]") {
  require_rejected(tiny_scene, {"material.Young: unknown key"}, "--set material.Young=1");
}

TEST_CASE("a --set with a list index out of range is named", "[cli]") {
  require_rejected(tiny_scene, {"--set boundary.7.pressure", "list index 7 is out of range"},
                   "--set boundary.7.pressure=1e5");
}

TEST_CASE("a --set names a list item as error messages do, or is told how", "[cli]") {
  require_rejected(tiny_scene, {"boundary[1].pressure: must be a number"}, "--set boundary[1].pressure=abc");
  require_rejected(tiny_scene, {"--set boundary.7.pressure", "list index 7 is out of range"},
                   "--set boundary[7].pressure=1e5");
  require_rejected(tiny_scene, {"--set boundary[x].pressure", "a list item is named by its index"},
                   "--set boundary[x].pressure=1e5");
}

TEST_CASE("a --set without '=' is rejected", "[cli]") {
  require_rejected(tiny_scene, {"--set material.E", "expected dotted.key=value"}, "--set material.E");
}

TEST_CASE("a --set of a bad value is checked like the file", "[cli]") {
  require_rejected(tiny_scene, {"boundary[1].pressure: must be a number"},
                   "--set boundary.1.pressure=abc");
}

TEST_CASE("an unwritable output folder is rejected before the solve", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  std::ofstream(dir.path / "a_file") << "not a folder\n";
  const Outcome o = perinom(dir, "run scene.yaml --out a_file/out");
  require_one_clear_error(o, {"--out a_file/out", "cannot be created or written (Not a directory)"});
  // An --out that is itself a file: the reason too (it said only "cannot be created or written").
  require_one_clear_error(perinom(dir, "run scene.yaml --out a_file"), {"--out a_file", "cannot be created or written (Not a directory)"});
}

TEST_CASE("a missing scene file is named", "[cli]") {
  ScratchDir dir;
  SECTION("perinom run") {
    require_one_clear_error(perinom(dir, "run no_such_scene.yaml --out out"),
                            {"no_such_scene.yaml", "cannot open the scene file"});
  }
  SECTION("perinom check") {
    require_one_clear_error(perinom(dir, "check no_such_scene.yaml"),
                            {"no_such_scene.yaml", "cannot open the scene file"});
  }
}

TEST_CASE("bad command line options are named", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  require_one_clear_error(perinom(dir, "run scene.yaml --frobnicate"), {"unknown option --frobnicate"});
  require_one_clear_error(perinom(dir, "run scene.yaml --threads abc"), {"--threads", "'abc'"});
  require_one_clear_error(perinom(dir, "run scene.yaml --out"), {"--out needs a value"});
  require_one_clear_error(perinom(dir, "run"), {"run needs exactly one scene file"});
}

TEST_CASE("an option of one value given twice is refused naming it and only --set repeats", "[cli]") {
  // The last one was used without a word: `--restart a --restart b` resumed b.
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  require_one_clear_error(perinom(dir, "run scene.yaml --out a --out b"), {"option --out is given twice"});
  require_one_clear_error(perinom(dir, "run scene.yaml --restart a --restart b"), {"option --restart is given twice"});
  require_one_clear_error(perinom(dir, "check scene.yaml --threads 1 --threads 2"), {"option --threads is given twice"});
  CHECK_FALSE(fs::exists(dir.path / "a"));
  CHECK_FALSE(fs::exists(dir.path / "b"));
  const Outcome o = perinom(dir, "check scene.yaml --set material.E=2e9 --set material.nu=0.3");
  INFO("stderr: " << o.err);
  CHECK(o.exit_code == 0);
}

TEST_CASE("a valid run writes its outputs and leaves no temporary file", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  const Outcome o = perinom(dir, "run scene.yaml --out results --threads 1 --set boundary.1.pressure=2e5");
  INFO("stderr: " << o.err);
  INFO("stdout: " << o.out);
  REQUIRE(o.exit_code == 0);
  CHECK(o.err.empty());
  const fs::path out = dir.path / "results";
  CHECK(fs::is_regular_file(out / "summary.json"));
  CHECK(fs::is_regular_file(out / "history.csv"));
  CHECK(fs::is_regular_file(out / "tiny.pvd"));
  CHECK(fs::is_regular_file(out / "probe_mid.csv"));
  int vtu = 0, tmp = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir.path)) {
    vtu += e.path().extension() == ".vtu";
    tmp += e.path().extension() == ".tmp";
  }
  CHECK(vtu >= 1);
  CHECK(fs::is_regular_file(out / "tiny_000000.vtu"));
  CHECK(tmp == 0);
  CHECK_FALSE(fs::exists(out / ".perinom-write-test"));
  const std::string summary = slurp(out / "summary.json");
  CHECK(summary.find("\"converged\": true") != std::string::npos);
  CHECK(summary.find("\"top_uy\"") != std::string::npos);
  // The ADR columns, then the reaction of the one support (the fixed bottom).
  CHECK(slurp(out / "history.csv").rfind("iteration,load_factor,residual,displacement_change,damping,"
                                         "boundary.0.Rx,boundary.0.Ry\n", 0) == 0);
}

// Gaps found by these tests and since fixed.

TEST_CASE("a duplicated key is rejected", "[cli]") {
  // yaml-cpp keeps the first of two equal keys; the reader never sees the second.
  const std::string s = with(tiny_scene, "  E: 1.0e9\n", "  E: 1.0e9\n  E: -3\n");
  require_rejected(s, {"material.E"});
}

TEST_CASE("a --set that walks into a scalar is bad input, not an internal error", "[cli]") {
  require_rejected(tiny_scene, {"--set material.E.x"}, "--set material.E.x=1");
}

TEST_CASE("a stress probe component with a space is rejected", "[cli]") {
  const std::string s = with(tiny_scene, "component: yy", "component: \" y\"");
  require_rejected(s, {"probes[1].component"});
}

TEST_CASE("a non-numeric --stabilization for bench is bad input", "[cli]") {
  ScratchDir dir;
  require_one_clear_error(perinom(dir, "bench force --dimension 2 --n 4 --stabilization abc"),
                          {"--stabilization"});
}

TEST_CASE("an unknown stabilization storage is named", "[cli]") {
  const std::string s = with(tiny_scene, "solver:\n", "model:\n  stabilization_storage: packed\nsolver:\n");
  require_rejected(s, {at_line(s, "stabilization_storage:", "model.stabilization_storage: must be auto, fused")});
}

TEST_CASE("the fused stabilization with a neighbour count is bad input", "[cli]") {
  // k nearest neighbours make families that are not symmetric: fused cannot apply.
  const std::string s = with(with(tiny_scene, "horizon: {ratio: 3.015}", "horizon: {neighbors: 12}"), "solver:\n",
                             "model:\n  formulation: classical\n  stabilization_storage: fused\nsolver:\n");
  require_rejected(s, {"model.stabilization_storage: fused needs symmetric families"});
}

TEST_CASE("the consistent formulation refuses a stabilization storage other than assembled", "[cli]") {
  // Its corrected G has not the first-order identities the fused and matrix-free forms need.
  for (const char* storage : {"fused", "matrix_free"}) {
    const std::string s = with(tiny_scene, "solver:\n",
                               std::string("model:\n  stabilization_storage: ") + storage + "\nsolver:\n");
    require_rejected(s, {at_line(s, "stabilization_storage:", "model.stabilization_storage:")});
  }
}

TEST_CASE("an operator order other than 1 or 2 is named", "[cli]") {
  const std::string s = with(tiny_scene, "solver:\n", "model:\n  operator_order: 3\nsolver:\n");
  require_rejected(s, {at_line(s, "operator_order:", "model.operator_order: must be 1 or 2")});
}

TEST_CASE("a fractional operator order is named", "[cli]") {
  const std::string s = with(tiny_scene, "solver:\n", "model:\n  operator_order: 1.5\nsolver:\n");
  require_rejected(s, {at_line(s, "operator_order:", "model.operator_order:")});
}

TEST_CASE("a first-order stabilization storage with operator order 2 is named", "[cli]") {
  const std::string s = with(tiny_scene, "solver:\n", "model:\n  operator_order: 2\n  stabilization_storage: fused\nsolver:\n");
  require_rejected(s, {"model.stabilization_storage: with operator_order 2 the stabilization is the second-order operator energy"});
}

TEST_CASE("an unknown --storage for bench is bad input", "[cli]") {
  ScratchDir dir;
  require_one_clear_error(perinom(dir, "bench force --dimension 2 --n 4 --storage packed"), {"--storage"});
}

TEST_CASE("material-point: a test outside Table 2 is bad input", "[cli]") {
  ScratchDir dir;
  require_one_clear_error(perinom(dir, "material-point --test 9"), {"--test"});
}

namespace {
/// The tiny scene with a Drucker-Prager material whose key `key` reads `value`.
std::string plastic_scene(const std::string& key, const std::string& value) {
  std::string dp = "  type: drucker_prager\n";
  for (const auto& [k, v] : {std::pair<std::string, std::string>{"friction_angle", "35.0"}, {"cohesion", "6.0e4"},
                             {"m0", "0.2"}, {"d0", "0.0"}, {"h", "0.0"}})
    dp += "  " + k + ": " + (k == key ? value : v) + "\n";
  std::string s = with(tiny_scene, "  type: linear_elastic\n", dp);
  return with(s, "  type: adr\n", "  type: lbc\n");
}
}  // namespace

TEST_CASE("the Drucker-Prager constants are checked, each by its key", "[cli]") {
  const struct {
    const char* key;
    const char* value;
    const char* message;
  } cases[] = {{"friction_angle", "90.0", "material.friction_angle: must lie in [0, 90) degrees"},
               {"friction_angle", "-1.0", "material.friction_angle: must lie in [0, 90) degrees"},
               {"cohesion", "-1.0", "material.cohesion: must be zero or positive"},
               {"d0", "1.5", "material.d0: must lie in [0, 1]"},
               {"d0", "-0.1", "material.d0: must lie in [0, 1]"},
               {"h", "-1.0", "material.h: must be zero or positive"},
               {"m0", "0.0", "material.m0: must lie in (0, 1]"},
               {"m0", "1.5", "material.m0: must lie in (0, 1]"}};
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.key << " = " << c.value) {
      const std::string s = plastic_scene(c.key, c.value);
      require_rejected(s, {at_line(s, std::string(c.key) + ": " + c.value, c.message)});
    }
  }
}

TEST_CASE("a valid Drucker-Prager scene passes the check, and Verlet is refused with it", "[cli]") {
  {
    ScratchDir dir;
    std::ofstream(dir.path / "scene.yaml") << plastic_scene("h", "0.0");
    const Outcome o = perinom(dir, "check scene.yaml");
    INFO("stderr: " << o.err);
    CHECK(o.exit_code == 0);
  }
  const std::string s = with(plastic_scene("h", "0.0"), "  type: lbc\n", "  type: verlet\n");
  require_rejected(s, {at_line(s, "type: verlet", "solver.type: verlet is not available with a drucker_prager material")});
}

namespace {

/// A valid thin plate: 10 x 10 cells, simply supported left and right, pressure everywhere.
const std::string plate_scene = R"(name: plate
dimension: 2
geometry:
  box: {min: [0.0, 0.0], max: [0.1, 0.1]}
  thickness: 0.002
discretization:
  dx: 0.01
  horizon: {ratio: 2.015}
material:
  type: linear_elastic
  E: 2.0e11
  nu: 0.3
  density: 7800.0
model:
  type: thin_plate
boundary:
  - region: left
    support: simply_supported
  - {region: right, support: clamped}
  - {region: all, pressure: 100.0}
probes:
  - {name: mid, point: [0.05, 0.05], field: deflection}
)";

}  // namespace

TEST_CASE("thin_plate keys are checked, each by its key", "[cli][plate]") {
  {
    ScratchDir dir;
    std::ofstream(dir.path / "scene.yaml") << plate_scene;
    const Outcome o = perinom(dir, "check scene.yaml");
    INFO("stderr: " << o.err);
    CHECK(o.exit_code == 0);
  }
  SECTION("an unknown support") {
    const std::string s = with(plate_scene, "support: simply_supported", "support: hinged");
    require_rejected(s, {at_line(s, "support: hinged", "boundary[0].support: must be simply_supported or clamped")});
  }
  SECTION("the thickness is required") {
    const std::string s = with(plate_scene, "  thickness: 0.002\n", "");
    require_rejected(s, {"geometry.thickness: is required for a thin_plate"});
  }
  SECTION("elasticity keys are refused") {
    const std::string s = with(plate_scene, "    support: simply_supported\n", "    fix: [x]\n");
    require_rejected(s, {at_line(s, "fix: [x]", "boundary[0].fix: a thin_plate boundary item takes")});
  }
  SECTION("a correspondence option is refused") {
    const std::string s = with(plate_scene, "  type: thin_plate\n", "  type: thin_plate\n  formulation: strong\n");
    require_rejected(s, {at_line(s, "formulation:", "model.formulation: is a correspondence option")});
  }
  SECTION("a pressure on supported edge nodes only is refused: it bent nothing, exit 0") {
    const std::string s = with(plate_scene, "{region: all, pressure: 100.0}",
                               "{region: {box: {min: [0.0, 0.0], max: [0.001, 0.1]}}, pressure: 100.0}");
    require_rejected(s, {at_line(s, "pressure: 100.0", "boundary[2].pressure: acts only on nodes of supported edges")});
  }
  SECTION("lbc has nothing to correct on an elastic plate") {
    require_rejected(plate_scene + "solver: {type: lbc}\n", {"solver.type: a thin_plate is elastic: solve it by adr or newton"});
  }
  SECTION("a plate takes no stages and no rigid-body constraint (its registry row says so)") {
    require_rejected(plate_scene + "constraints: rigid_body\n",
                     {"constraints: rigid_body does not apply to a thin_plate"});
    require_rejected(plate_scene + "stages:\n  - {name: one, boundary: []}\n",
                     {"stages: a thin_plate is loaded in one stage"});
  }
  SECTION("a deflection probe outside a plate scene") {
    const std::string s = with(tiny_scene, "    component: y\n", "    field: deflection\n");
    require_rejected(s, {at_line(s, "field: deflection", "probes[0].field: deflection is the field of a thin_plate")});
  }
  SECTION("Newton solves a plate, and checks ADR's") {
    for (const char* solver : {"solver: {type: newton}\n", "solver: {type: adr, check: newton}\n"}) {
      ScratchDir dir;
      std::ofstream(dir.path / "scene.yaml") << plate_scene + solver;
      const Outcome o = perinom(dir, "run scene.yaml --out out");
      INFO(solver << "stderr: " << o.err);
      CHECK(o.exit_code == 0);
    }
  }
  SECTION("a plate probe measures the deflection") {
    const std::string s = with(plate_scene, "field: deflection", "field: displacement, component: x");
    require_rejected(s, {at_line(s, "field: displacement", "probes[0].field: a thin_plate probe measures the deflection")});
  }
  SECTION("a support outside a plate scene") {
    const std::string s = with(tiny_scene, "    fix: [x, y]\n", "    support: clamped\n");
    require_rejected(s, {at_line(s, "support:", "boundary[0].support: edge supports belong to model.type thin_plate")});
  }
}

TEST_CASE("finite rotation is refused without a plastic material, an unknown kinematics and a misplaced follower pressure by key", "[cli]") {
  {
    const std::string s = with(tiny_scene, "solver:\n", "model:\n  kinematics: finite_rotation\nsolver:\n");
    require_rejected(s, {at_line(s, "kinematics:", "model.kinematics: finite_rotation is implemented for the drucker_prager material only")});
  }
  {
    const std::string s = with(plastic_scene("h", "0.0"), "solver:\n", "model:\n  kinematics: large\nsolver:\n");
    require_rejected(s, {at_line(s, "kinematics:", "model.kinematics: must be small_strain or finite_rotation")});
  }
  {
    const std::string s = with(plastic_scene("h", "0.0"), "solver:\n", "model:\n  follower_pressure: true\nsolver:\n");
    require_rejected(s, {at_line(s, "follower_pressure:", "model.follower_pressure: needs kinematics: finite_rotation")});
  }
  {
    const std::string s = with(plastic_scene("h", "0.0"), "solver:\n",
                               "model:\n  kinematics: finite_rotation\n  follower_pressure: sometimes\nsolver:\n");
    require_rejected(s, {at_line(s, "follower_pressure:", "model.follower_pressure: must be true or false")});
  }
}

TEST_CASE("Verlet refuses the improved and strong formulations by model.formulation, unless allowed", "[cli]") {
  // Their strong-form rows make K non-symmetric: M^-1 K has complex and negative eigenvalues,
  // which explicit dynamics grows exponentially whatever the step (issue 14).
  for (const std::string f : {"improved", "strong"}) {
    DYNAMIC_SECTION(f) {
      const std::string s = with(with(tiny_scene, "boundary:\n", "model: {formulation: " + f + "}\nboundary:\n"),
                                 "  type: adr\n", "  type: verlet\n");
      require_rejected(s, {at_line(s, "model:", "model.formulation: " + f + " is non-symmetric and unstable in "
                                                "explicit dynamics"), "use consistent or classical",
                           "solver.allow_unstable: true"});
    }
  }
  SECTION("solver.allow_unstable: true lets it run") {
    const std::string s = with(with(tiny_scene, "boundary:\n", "model: {formulation: improved}\nboundary:\n"),
                               "  type: adr\n", "  type: verlet\n  allow_unstable: true\n");
    ScratchDir dir;
    std::ofstream(dir.path / "scene.yaml") << s;
    const Outcome o = perinom(dir, "check scene.yaml");
    INFO("stderr: " << o.err);
    CHECK(o.exit_code == 0);
  }
}

TEST_CASE("a relative tolerance of 1 or more is named: it let a run stop 'converged' at its first iteration", "[cli]") {
  // solver.tolerance 2 with displacement_tolerance 1 "converged" after 1 iteration with an
  // equilibrium error of 1 and the top displacement at 4% of the answer, exit 0.
  for (const std::string key : {"tolerance", "displacement_tolerance", "step_tolerance", "yield_tolerance"}) {
    INFO(key);
    const std::string s = key == "tolerance"
                              ? with(tiny_scene, "  tolerance: 1.0e-6\n", "  tolerance: 2.0\n")
                              : with(tiny_scene, "  tolerance: 1.0e-6\n", "  tolerance: 1.0e-6\n  " + key + ": 1.0\n");
    require_rejected(s, {"solver." + key + ": must lie in (0, 1): it is relative"});
  }
}

TEST_CASE("a non-positive energy tolerance is named", "[cli]") {
  const std::string s = with(tiny_scene, "  type: adr\n", "  type: verlet\n  energy_tolerance: 0\n");
  require_rejected(s, {at_line(s, "energy_tolerance:", "solver.energy_tolerance: must be positive")});
}

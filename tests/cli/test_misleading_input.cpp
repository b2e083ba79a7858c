// Input that once gave a misleading outcome: a scene silently cut at a stray "---", an
// internal error (exit 4) for a key or an index YAML or std::stoul could not take, a name
// that put files outside the output folder, command-line numbers read loosely, a spacing
// whose lattice count overflowed, and a message about the wrong key. Each now ends in exit
// code 2 and one line naming what is wrong (or, for `plane: null`, in the documented
// "null counts as absent").
#include "../support/cli.hpp"

using namespace cli_test;

TEST_CASE("a second YAML document (a stray ---) is refused with the separator's line", "[cli]") {
  const std::string s = with(tiny_scene, "material:\n", "---\nmaterial:\n");
  require_rejected(s, {"scene.yaml:" + std::to_string(line_of(s, "---")) + ":", "second YAML document"});
  const std::string end = with(tiny_scene, "material:\n", "...\nmaterial:\n");
  require_rejected(end, {"scene.yaml:" + std::to_string(line_of(end, "...")) + ":", "second YAML document"});
}

TEST_CASE("a leading --- (an explicit document start) is one document and valid", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << "# a comment\n---\n" + tiny_scene;
  const Outcome o = perinom(dir, "check scene.yaml");
  INFO("stderr: " << o.err);
  CHECK(o.exit_code == 0);
}

TEST_CASE("a list or a mapping used as a key is bad input naming the key", "[cli]") {
  SECTION("[a, b]: c at the top") {
    const std::string s = with(tiny_scene, "dimension: 2\n", "dimension: 2\n[a, b]: c\n");
    require_rejected(s, {at_line(s, "[a, b]: c", "[a, b]: a key must be a plain name")});
  }
  SECTION("? [a, b] in a mapping") {
    const std::string s = with(tiny_scene, "  E: 1.0e9\n", "  E: 1.0e9\n  ? [a, b]\n");
    require_rejected(s, {"material.[a, b]: a key must be a plain name"});
  }
  SECTION("{x: 1}: 2 in a list item") {
    const std::string s = with(tiny_scene, "    fix: [x, y]\n", "    fix: [x, y]\n    {x: 1}: 2\n");
    require_rejected(s, {"boundary[0].{x: 1}: a key must be a plain name"});
  }
}

TEST_CASE("a --set list index too long for any integer is out of range, not an internal error", "[cli]") {
  require_rejected(tiny_scene, {"--set boundary.99999999999999999999.pressure", "list index 99999999999999999999 is out of range"},
                   "--set boundary.99999999999999999999.pressure=1");
  require_rejected(tiny_scene, {"list index 2 is out of range"}, "--set boundary.2.pressure=1");
  require_rejected(tiny_scene, {"list index 0002 is out of range"}, "--set boundary.0002.pressure=1");
}

TEST_CASE("a --set index with leading zeros still reaches its item", "[cli]") {
  require_rejected(tiny_scene, {"boundary[1].pressure: must be a number"}, "--set boundary.0001.pressure=abc");
}

TEST_CASE("the name is a safe file name: letters, digits, _ - . but not . or ..", "[cli]") {
  for (const std::string bad : {"\"..\"", "\".\"", "\"a b\"", "\"a\\nb\"", "\"a\\0b\"", "a/b", "\"a\\\\b\"", "\"\"", "\"a:b\"",
                                "\"~\""}) {
    DYNAMIC_SECTION("name: " << bad) {
      const std::string s = with(tiny_scene, "name: tiny", "name: " + bad);
      require_rejected(s, {at_line(s, "name:", "name: must be made of letters, digits")});
    }
  }
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << with(tiny_scene, "name: tiny", "name: Run-2.b_1");
  const Outcome o = perinom(dir, "check scene.yaml");
  INFO("stderr: " << o.err);
  CHECK(o.exit_code == 0);
}

TEST_CASE("a name too long for the file names made from it is refused before the solve", "[cli]") {
  // 241 characters ran the whole solve, then NAME_000000.vtu.tmp was too long to create.
  const std::string s = with(tiny_scene, "name: tiny", "name: " + std::string(201, 'n'));
  require_rejected(s, {at_line(s, "name:", "name: is 201 characters long: at most 200")});
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << with(tiny_scene, "name: tiny", "name: " + std::string(200, 'n'));
  const Outcome o = perinom(dir, "run scene.yaml --out out");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  CHECK(o.exit_code == 0);
}

TEST_CASE("an empty --out is an error, not the default folder", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  require_one_clear_error(perinom(dir, "run scene.yaml --out ''"), {"--out", "empty"});
  CHECK_FALSE(fs::exists(dir.path / "out"));
}

TEST_CASE("command-line numbers are read whole and within their bounds", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  for (const std::string bad : {"2x", "4294967297", "0", "-1", "1025", "", "1.5", " 2"}) {
    DYNAMIC_SECTION("--threads '" << bad << "'") {
      require_one_clear_error(perinom(dir, "check scene.yaml --threads '" + bad + "'"), {"--threads"});
    }
  }
  SECTION("the bench and material-point options") {
    require_one_clear_error(perinom(dir, "bench force --dimension 2 --n 4x"), {"--n", "'4x'"});
    require_one_clear_error(perinom(dir, "bench force --dimension 4 --n 4"), {"--dimension", "out of range"});
    require_one_clear_error(perinom(dir, "bench force --dimension 3 --n 2000"), {"--n: 2000^3 particles", "2e9"});
    require_one_clear_error(perinom(dir, "bench force --dimension 2 --n 4 --stabilization 0.5x"), {"--stabilization"});
    require_one_clear_error(perinom(dir, "material-point --test 2x"), {"--test", "'2x'"});
    require_one_clear_error(perinom(dir, "material-point --substeps 99999999999999999999"), {"--substeps", "out of range"});
  }
  SECTION("1 and 2 threads are accepted") {
    for (const char* n : {"1", "2"}) {
      const Outcome o = perinom(dir, std::string("check scene.yaml --threads ") + n);
      INFO("stderr: " << o.err);
      CHECK(o.exit_code == 0);
    }
  }
}

TEST_CASE("a spacing whose lattice count overflows is refused by key, before any integer conversion", "[cli]") {
  for (const std::string dx : {"1.0e-300", "1.0e-9", "1.0e308", "0.05"}) {
    DYNAMIC_SECTION("dx = " << dx) {
      const std::string s = with(tiny_scene, "dx: 0.001", "dx: " + dx);
      require_rejected(s, {at_line(s, "dx:", "discretization.dx: ")});
    }
  }
}

TEST_CASE("a 1 m cube at dx = 0.1 mm is refused by key, a 3-D lattice count in double", "[cli]") {
  const std::string s = R"(name: cube
dimension: 3
geometry: {box: {min: [0, 0, 0], max: [1, 1, 1]}}
discretization: {dx: 1.0e-4, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0}
)";
  require_rejected(s, {"scene.yaml:4: discretization.dx: gives about", "2e9"});
}

TEST_CASE("an unterminated quote is a YAML error with its line, not a message about another key", "[cli]") {
  const std::string s = with(tiny_scene, "name: tiny", "name: \"tiny");
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << s;
  const Outcome o = perinom(dir, "check scene.yaml");
  require_one_clear_error(o, {"scene.yaml:", "not valid YAML"});
  CHECK(o.err.find("dimension") == std::string::npos);
}

TEST_CASE("plane: null in a 3-D scene counts as absent, as the docs say of every null", "[cli]") {
  const std::string s = R"(name: cube
dimension: 3
geometry: {box: {min: [0, 0, 0], max: [0.004, 0.004, 0.004]}}
discretization: {dx: 0.001, horizon: {ratio: 2.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0, plane: null}
boundary:
  - {region: bottom, fix: [x, y, z]}
)";
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << s;
  const Outcome o = perinom(dir, "check scene.yaml");
  INFO("stderr: " << o.err);
  CHECK(o.exit_code == 0);
  // A plane condition given in 3-D is still refused.
  require_rejected(with(s, "plane: null", "plane: strain"), {"material.plane: only 2-D scenes"});
}

TEST_CASE("a load that acts only on components held at their particles is refused, naming the support", "[cli]") {
  // The top both held in y (at its particles) and pulled in y: with the classical formulation
  // the traction sits on those particles and went whole into the reaction, exit 0 and a body
  // that did not move. Through the consistent formulation's trace it reaches the particles
  // below, and the body deforms: accepted.
  const std::string held = with(tiny_scene, "  - region: top\n    pressure: 1.0e6\n",
                                "  - region: top\n    fix: [y]\n  - region: top\n    traction: [0.0, 1.0e6]\n");
  const std::string classical = with(held, "solver:\n", "model: {type: correspondence, formulation: classical}\nsolver:\n");
  SECTION("classical: refused") {
    require_rejected(classical, {"scene.yaml:", "boundary[2].traction: acts only on components held at their particles "
                                 "(by boundary[1]): the whole load goes into the support's reaction"});
  }
  SECTION("the x component is free: accepted") {
    ScratchDir dir;
    std::ofstream(dir.path / "scene.yaml") << with(classical, "traction: [0.0, 1.0e6]", "traction: [1.0e5, 1.0e6]");
    CHECK(perinom(dir, "check scene.yaml").exit_code == 0);
  }
  SECTION("consistent: accepted") {
    ScratchDir dir;
    std::ofstream(dir.path / "scene.yaml") << held;
    CHECK(perinom(dir, "check scene.yaml").exit_code == 0);
  }
}

TEST_CASE("a bad --set value is named by its --set option, not by a line of the scene file", "[cli]") {
  // --set material.E=abc was reported as "scene.yaml:1: material.E: must be a number".
  require_rejected(tiny_scene, {"--set material.E=abc: material.E: must be a number"}, "--set material.E=abc");
  require_rejected(tiny_scene, {"--set boundary.1={region: top, pressure: x}: boundary[1].pressure: must be a number"},
                   "--set 'boundary.1={region: top, pressure: x}'");
  // A key of the file itself keeps its line.
  const std::string s = with(tiny_scene, "  nu: 0.25\n", "  nu: 0.75\n");
  require_rejected(s, {at_line(s, "nu:", "material.nu")}, "--set material.E=2.0e9");
}

TEST_CASE("a horizon more than twice the body is refused by key: every particle would bond with every other", "[cli]") {
  // horizon.ratio 1e6 on the Kalthoff plate (a fuzzed scene) built 10 million bonds and a
  // gigabyte before any answer.
  const std::string s = with(tiny_scene, "ratio: 3.015", "ratio: 1.0e6");
  require_rejected(s, {at_line(s, "ratio: 1.0e6", "discretization.horizon.ratio: gives a horizon"), "every particle"});
}

TEST_CASE("probes whose files would overwrite another output are refused, naming the file", "[cli]") {
  // A line probe 'top_uy_history' wrote over the point probe top_uy's load-step history, and
  // a line probe '000000' of the scene 'probe' over its first snapshot's .csv, with exit 0.
  SECTION("a line probe on a point probe's history") {
    const std::string s = with(tiny_scene, "  - name: mid\n", "  - name: top_uy_history\n");
    require_rejected(s, {at_line(s, "name: top_uy_history", "probes[1].name: probe_top_uy_history.csv is probe 'top_uy''s file")});
  }
  SECTION("a line probe on a snapshot's .csv") {
    const std::string s = with(with(tiny_scene, "name: tiny", "name: probe"), "  - name: mid\n", "  - name: \"000012\"\n");
    require_rejected(s, {"probes[1].name: probe_000012.csv is the name of a snapshot's .csv of the scene 'probe'"});
  }
}

TEST_CASE("probe names that only look alike are accepted", "[cli]") {
  const std::string s = with(with(tiny_scene, "name: tiny", "name: probe"), "  - name: mid\n", "  - name: \"00001\"\n");
  require_valid(with(s, "  - name: top_uy\n", "  - name: mid_history\n"));
}

TEST_CASE("a --set with no value, or a key with a space, is refused naming the --set", "[cli]") {
  // solver.type= (null: absent) ran ADR with exit 0; ' material.nu' was blamed on the file.
  SECTION("no value") {
    require_rejected(tiny_scene, {"--set solver.type: no value after '='", "solver.type=null"}, "--set solver.type=");
  }
  SECTION("a space in the key") {
    require_rejected(tiny_scene, {"--set ' material.E': a key has no spaces"}, "--set ' material.E=2e9'");
  }
  SECTION("an empty key between dots") {
    require_rejected(tiny_scene, {"--set material..E: an empty key between dots"}, "--set material..E=2e9");
  }
  SECTION("null on purpose still removes an optional key") { require_valid(tiny_scene, "--set solver.tolerance=null"); }
}

TEST_CASE("a horizon that a lattice's wider spacing shrinks says so, beside the particle", "[cli]") {
  // dx 12.4 mm on the plate's 0.5 m side: 40 cells of 12.5 mm, and delta = 2.015 dx spans
  // 1.999 spacings: the second ring lost, and the message blamed a ghost node alone.
  ScratchDir dir;
  const Outcome o = perinom(dir, "check '" PERINOM_SOURCE_DIR "/examples/thin_plate_clamped.yaml' --set discretization.dx=0.0124");
  require_one_clear_error(o, {"discretization.horizon.ratio", "the lattice's spacing is 0.0125 m", "more than dx = 0.0124 m",
                              "spans 1.999 of its spacings, not 2.015: a dx that divides the box's sides"});
}

TEST_CASE("an option of another command is refused, naming it", "[cli]") {
  // run --spectrum ran no stability check, check --out x --keep ignored both: exit 0.
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  require_one_clear_error(perinom(dir, "run scene.yaml --out out --spectrum"),
                          {"option --spectrum is not an option of 'perinom run'"});
  require_one_clear_error(perinom(dir, "check scene.yaml --out x"), {"option --out is not an option of 'perinom check'"});
  require_one_clear_error(perinom(dir, "material-point --set a=b"),
                          {"option --set is not an option of 'perinom material-point'"});
  require_one_clear_error(perinom(dir, "bench refresh --dimension 2 --n 4 --check"),
                          {"option --check is not an option of 'perinom bench refresh'"});
  require_one_clear_error(perinom(dir, "bench force --dimension 2 --n 4 --bonds 5"),
                          {"option --bonds is not an option of 'perinom bench force'"});
  require_valid(tiny_scene, "--threads 1 --max-memory 2G");
}

TEST_CASE("null counts as absent for a key another setting reads", "[cli]") {
  // damage.f_t: null with the stretch criterion read "damage.f_t: unknown key".
  require_valid(tiny_scene, "--set model.formulation=classical --set damage.criterion=stretch --set damage.s_c=1e-3 "
                            "--set damage.f_t=null --set solver.type=verlet --set solver.steps=10");
}

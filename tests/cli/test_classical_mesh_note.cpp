// The classical formulation on a body from a mesh: its surface effect is larger on an
// irregular cloud (verification/formulation/classical_mesh.py: reactions -7.5% and -19% on an
// L-shaped body of triangles under a uniform strain). Check and run say so, and summary.json
// lists the note; the consistent formulation and the lattice get no such note.
#include "../support/cli.hpp"

using namespace cli_test;

namespace {

/// The 16 mm square of triangles from tests/data, its bottom held, its top pulled.
const std::string square = R"(name: square
dimension: 2
geometry: {mesh: square.msh}
discretization: {dx: 0.002, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0}
model: {formulation: classical}
boundary:
  - {region: {group: bottom}, fix: [x, y]}
  - {region: {group: top}, traction: [0.0, 1.0e6]}
solver: {type: direct}
)";

}  // namespace

TEST_CASE("the classical formulation on a mesh gets a note from check and run, listed in summary.json", "[cli]") {
  ScratchDir dir;
  fs::copy_file(PERINOM_SOURCE_DIR "/tests/data/square_tri.msh", dir.path / "square.msh");
  std::ofstream(dir.path / "classical.yaml") << square;
  std::ofstream(dir.path / "consistent.yaml") << with(square, "formulation: classical", "formulation: consistent");
  std::ofstream(dir.path / "lattice.yaml")
      << with(with(with(square, "{mesh: square.msh}", "{box: {min: [0.0, 0.0], max: [0.016, 0.016]}}"),
                   "{group: bottom}", "bottom"),
              "{group: top}", "top");
  const std::string said = "model.formulation classical on a body from a mesh: its surface effect is larger";
  const Outcome check = perinom(dir, "check classical.yaml");
  INFO(check.out << check.err);
  CHECK(check.exit_code == 0);
  CHECK(check.out.find("  formulation     " + said) != std::string::npos);
  const Outcome run = perinom(dir, "run classical.yaml --out out");
  INFO(run.out << run.err);
  REQUIRE(run.exit_code == 0);
  CHECK(run.out.find("perinom: note: " + said) != std::string::npos);
  const std::string summary = slurp(dir.path / "out" / "summary.json");
  REQUIRE(summary.find("\"notes\": [") != std::string::npos);
  CHECK(summary.find("\"" + said, summary.find("\"notes\": [")) != std::string::npos);
  for (const char* quiet : {"consistent.yaml", "lattice.yaml"}) {
    const Outcome o = perinom(dir, std::string("run ") + quiet + " --out " + quiet + ".out");
    INFO(quiet << ": " << o.out << o.err);
    CHECK(o.exit_code == 0);
    CHECK(o.out.find("surface effect") == std::string::npos);
    CHECK(slurp(dir.path / (std::string(quiet) + ".out") / "summary.json").find("surface effect") == std::string::npos);
  }
}

// A nearly incompressible body few particles across locks in bending (the plane-strain
// cantilever 4 particles thick at nu = 0.499: 70% too stiff, exit 0): check and run warn,
// naming nu, lambda / mu and where the body is thin. Plane stress (no incompressibility in
// the plane), nu = 0.3 and classical with operator_order 2 (which did not lock) get no
// warning.
#include "../support/cli.hpp"

using namespace cli_test;

TEST_CASE("a nearly incompressible body few particles across gets a locking warning from check and run", "[cli]") {
  const std::string soft = with(tiny_scene, "nu: 0.25", "nu: 0.499");
  ScratchDir dir;
  std::ofstream(dir.path / "soft.yaml") << soft;
  std::ofstream(dir.path / "stiff.yaml") << tiny_scene;
  std::ofstream(dir.path / "stress.yaml") << with(soft, "density: 1000.0", "density: 1000.0\n  plane: stress");
  std::ofstream(dir.path / "classical.yaml") << soft + "model: {formulation: classical, operator_order: 2}\n";
  const Outcome check = perinom(dir, "check soft.yaml");
  INFO(check.out << check.err);
  CHECK(check.exit_code == 0);
  CHECK(check.out.find("locking         warning: material.nu = 0.499 is nearly incompressible (lambda / mu = 499) and "
                       "the body is 10 particles across along") != std::string::npos);
  CHECK(check.out.find("model.formulation consistent with operator_order 2 locks in bending") != std::string::npos);
  const Outcome run = perinom(dir, "run soft.yaml --out out");
  INFO(run.out << run.err);
  CHECK(run.exit_code == 0);
  CHECK(run.out.find("perinom: warning: material.nu = 0.499 is nearly incompressible") != std::string::npos);
  // nu to as many digits as given: 0.4999999999 read "nu = 0.5" (%g), which is refused.
  std::ofstream(dir.path / "nines.yaml") << with(tiny_scene, "nu: 0.25", "nu: 0.4999999999");
  const Outcome nines = perinom(dir, "check nines.yaml");
  INFO(nines.out << nines.err);
  CHECK(nines.out.find("warning: material.nu = 0.4999999999 is nearly incompressible") != std::string::npos);
  for (const char* quiet : {"stiff.yaml", "stress.yaml", "classical.yaml"}) {
    const Outcome o = perinom(dir, std::string("check ") + quiet);
    INFO(quiet << ": " << o.out << o.err);
    CHECK(o.exit_code == 0);
    CHECK(o.out.find("locking") == std::string::npos);
  }
}

TEST_CASE("a Drucker-Prager body gets the plastic collapse note from check and run, an elastic one does not", "[cli]") {
  // Prandtl's footing carried 1.24 times the limit load at 8 particles across its half-width
  // and was still rising: a limit load read from such a run is not converged.
  const std::string plastic = with(tiny_scene, "type: linear_elastic", "type: drucker_prager\n  friction_angle: 0.0\n  cohesion: 1.0e6");
  ScratchDir dir;
  std::ofstream(dir.path / "plastic.yaml") << plastic;
  std::ofstream(dir.path / "elastic.yaml") << tiny_scene;
  const Outcome check = perinom(dir, "check plastic.yaml");
  INFO(check.out << check.err);
  CHECK(check.exit_code == 0);
  CHECK(check.out.find("collapse        material drucker_prager: a body that collapses by a mechanism") != std::string::npos);
  const Outcome run = perinom(dir, "run plastic.yaml --out out");
  INFO(run.out << run.err);
  CHECK(run.exit_code == 0);
  CHECK(run.out.find("perinom: note: material drucker_prager: a body that collapses") != std::string::npos);
  CHECK(perinom(dir, "check elastic.yaml").out.find("collapse") == std::string::npos);
}

// Newton and direct on a nearly incompressible body (the plane-strain cantilever at nu = 0.499,
// 16 particles through the thickness, lambda / mu = 499): both give the same tip. Before,
// Newton stopped with KIN_LINESEARCH_NONCONV (exit 3) at a reported residual of 2.1e-11
// against its tolerance 1e-10, a stall KINSOL's own scaled test makes; it is now accepted when
// the reported residual meets the tolerance. Rounding decides whether KINSOL stalls, so on
// another machine Newton may converge without the acceptance; the test then checks the answer.
#include "../support/cli.hpp"

using namespace cli_test;

TEST_CASE("Newton and direct agree on a nearly incompressible cantilever, both converged", "[cli][solvers]") {
  ScratchDir dir;
  const std::string scene = "'" PERINOM_SOURCE_DIR "/verification/formulation/cantilever_2d.yaml'";
  const std::string sets = " --set material.plane=strain --set material.nu=0.499 --set discretization.dx=0.000625";
  const Outcome newton = perinom(dir, "run " + scene + " --out newton" + sets);
  INFO(newton.out << newton.err);
  REQUIRE(newton.exit_code == 0);
  const Outcome direct = perinom(dir, "run " + scene + " --out direct --set solver.type=direct" + sets);
  INFO(direct.out << direct.err);
  REQUIRE(direct.exit_code == 0);
  const double a = json_number(slurp(dir.path / "newton" / "summary.json"), "tip_uy");
  const double b = json_number(slurp(dir.path / "direct" / "summary.json"), "tip_uy");
  CHECK(a == Approx(b).epsilon(1e-7));
  CHECK(b == Approx(-1.4991e-4).epsilon(1e-3));  // measured; CalculiX -1.4966e-4 (+0.2%)
}

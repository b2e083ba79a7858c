// solver.check: newton warns when its answer and the run's are not one answer (1% apart): the
// number alone was printed for a slender cantilever 15% off, ADR stopped early by a loose
// tolerance, and nothing said it mattered.
#include "../support/cli.hpp"

using namespace cli_test;

TEST_CASE("the Newton check warns when ADR stopped 15 percent short and not when it converged", "[cli][newton]") {
  // The 2-D cantilever (4 particles across, 40 along): ADR's relative residual is not an error
  // bound on a slender body: measured 1.5e-1, 1.8e-2, 1.8e-3, 1.8e-6 from Newton at
  // tolerances 1e-3, 1e-4, 1e-5, 1e-8 (both tolerances set alike).
  ScratchDir d;
  const auto run = [&](const std::string& tolerance) {
    return perinom(d, "run '" PERINOM_SOURCE_DIR "/verification/formulation/cantilever_2d.yaml' --out out "
                      "--set solver.type=adr --set solver.check=newton --set solver.tolerance=" + tolerance +
                      " --set solver.displacement_tolerance=" + tolerance);
  };
  const std::string warning = "perinom: warning: solver.check: newton: the run's answer and Newton's differ by";
  const Outcome loose = run("1e-3");
  INFO(loose.out << loose.err);
  REQUIRE(loose.exit_code == 0);
  CHECK(loose.out.find(warning) != std::string::npos);
  CHECK(slurp(d.path / "out" / "summary.json").find("the run's answer and Newton's differ by") != std::string::npos);
  const Outcome tight = run("1e-8");
  INFO(tight.out << tight.err);
  REQUIRE(tight.exit_code == 0);
  CHECK(tight.out.find("perinom: Newton check: displacement differs by") != std::string::npos);
  CHECK(tight.out.find(warning) == std::string::npos);
}

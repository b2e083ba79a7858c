// `perinom check` says which linear solver a Newton solve will factor with (UMFPACK by
// default, KLU on request), and says nothing of it where no Newton solve runs.
#include "../support/cli.hpp"

#include <fstream>

using namespace cli_test;

TEST_CASE("perinom check names Newton's linear solver where Newton runs", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  const auto line = [&](const std::string& args) {
    const Outcome o = perinom(dir, "check scene.yaml " + args);
    INFO(o.out << o.err);
    REQUIRE(o.exit_code == 0);
    const auto at = o.out.find("  solver          ");
    REQUIRE(at != std::string::npos);
    return o.out.substr(at + 18, o.out.find('\n', at) - at - 18);
  };
  CHECK(line("--set solver.type=newton") == "newton, Newton's linear solver umfpack");
  CHECK(line("--set solver.type=newton --set solver.linear_solver=klu") == "newton, Newton's linear solver klu");
  CHECK(line("--set solver.check=newton") == "adr, Newton's linear solver umfpack");
  CHECK(line("") == "adr");
  CHECK(line("--set solver.type=direct") == "direct");
}

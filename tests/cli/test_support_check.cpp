// The warning of a static run whose supports leave a rigid motion free, as a user meets it,
// on the vibrating bar of the examples (left end held, right end pulled) solved by ADR. Each
// test runs the real binary in its own temporary folder.
#include <catch2/catch.hpp>

#include <string>

#include "../support/bar_run.hpp"

using bar_test::bar;
using bar_test::Outcome;

TEST_CASE("a static run names the rigid motion its supports leave free, and only then", "[cli][supports]") {
  const std::string adr = "--set discretization.dx=0.002 --set solver.type=adr";
  const Outcome held = bar("supports_held", "run", adr + " --out out");
  INFO(held.out << held.err);
  CHECK(held.exit_code == 0);
  CHECK(held.err.find("rigid motion") == std::string::npos);
  // The left end held along the bar only: the bar can slide across it. The pull is along the
  // bar, so ADR still balances: the warning says what could go wrong, it does not stop the run.
  const Outcome slides = bar("supports_slide", "run", adr + " --out out --set 'boundary.0.fix=[x]'");
  INFO(slides.out << slides.err);
  CHECK(slides.exit_code == 0);
  CHECK(slides.err.find("perinom: warning: boundary: the supports leave the body 1 rigid motion(s) free: it can move "
                        "along (0, 1).") != std::string::npos);
  // Explicit dynamics may move freely: no warning.
  const Outcome flies = bar("supports_verlet", "run", "--set discretization.dx=0.002 --set solver.steps=10 --out out "
                            "--set 'boundary.0.fix=[x]'");
  INFO(flies.out << flies.err);
  CHECK(flies.exit_code == 0);
  CHECK(flies.err.find("rigid motion") == std::string::npos);
}

// A point pressure on a thin plate, as a user meets it: the node nearest the point takes it,
// as a correspondence point region's particle does, so a point off the plate is refused by
// the same check and a point midway between nodes gets the same tie note. Each test runs the
// real binary in its own temporary folder.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>

#include "../support/cli.hpp"

using namespace cli_test;

namespace {

/// A 0.5 m square plate of 20 x 20 cells, simply supported left and right, a point load.
std::string point_loaded_plate(const std::string& point) {
  return R"(name: plate
dimension: 2
geometry:
  box: {min: [0.0, 0.0], max: [0.5, 0.5]}
  thickness: 0.01
discretization:
  dx: 0.025
  horizon: {ratio: 2.015}
material: {type: linear_elastic, E: 210.0e9, nu: 0.3, density: 7800.0}
model: {type: thin_plate}
boundary:
  - {region: left, support: simply_supported}
  - {region: right, support: simply_supported}
  - {region: {point: )" + point + R"(}, pressure: 1.0e5}
solver: {type: newton}
probes:
  - {name: mid, point: [0.25, 0.25], field: deflection}
)";
}

}  // namespace

TEST_CASE("a plate point load off the plate is refused by its key, as a correspondence one is", "[cli][plate]") {
  // 2.1 m off the plate it loaded the corner node, exit 0 (only the left edge supported), or
  // was refused for acting on supported edge nodes only (all four).
  const std::string needle = "region.point: the point is 2.12132 m from the nearest particle";
  SECTION("left edge supported") {
    const std::string s = with(point_loaded_plate("[2.0, 2.0]"), "  - {region: right, support: simply_supported}\n", "");
    require_rejected(s, {at_line(s, "point: [2.0", "boundary[1]." + needle), "outside the body"});
  }
  SECTION("all four edges supported: the point is off the plate before it is on a supported edge") {
    const std::string s = with(point_loaded_plate("[2.0, 2.0]"), "boundary:\n",
                               "boundary:\n  - {region: bottom, support: simply_supported}\n"
                               "  - {region: top, support: simply_supported}\n");
    require_rejected(s, {at_line(s, "point: [2.0", "boundary[4]." + needle), "outside the body"});
  }
}

TEST_CASE("a plate point load midway between two nodes is noted by run and check", "[cli][plate]") {
  // 0.2625 lies midway between the nodes at 0.25 and 0.275: the lower-numbered took the load
  // without a word.
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << point_loaded_plate("[0.2625, 0.25]");
  const std::string tie = "boundary.2.region.point is as near 2 particles: particle ";
  const Outcome checked = perinom(dir, "check scene.yaml");
  INFO(checked.out << checked.err);
  CHECK(checked.exit_code == 0);
  CHECK(checked.out.find("  tie             " + tie) != std::string::npos);
  CHECK(checked.out.find("0.0125 m from the point") != std::string::npos);
  const Outcome ran = perinom(dir, "run scene.yaml --out out");
  INFO(ran.out << ran.err);
  CHECK(ran.exit_code == 0);
  CHECK(ran.out.find("perinom: note: " + tie) != std::string::npos);
  // A point on a node is no tie.
  std::ofstream(dir.path / "on_node.yaml") << point_loaded_plate("[0.25, 0.25]");
  const Outcome on = perinom(dir, "check on_node.yaml");
  CHECK(on.exit_code == 0);
  CHECK(on.out.find("region.point is as near") == std::string::npos);
}

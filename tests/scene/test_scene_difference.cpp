#include <catch2/catch.hpp>

#include <string>

#include "../support/cli.hpp"
#include "perinom/scene/scene.hpp"
#include "perinom/scene/scene_difference.hpp"

using namespace perinom;

namespace {

std::string canonical(const std::string& text, const std::vector<std::string>& sets = {}) {
  return parse_scene(text, "scene.yaml", sets).canonical;
}

}  // namespace

TEST_CASE("a scene is the same scene with other output keys, comments or key order", "[scene][checkpoint]") {
  const std::string& s = cli_test::tiny_scene;
  const std::string base = canonical(s);
  CHECK_FALSE(scene_difference(base, canonical(s, {"output.vtk_every=5", "output.checkpoint_every=7"})));
  CHECK_FALSE(scene_difference(base, canonical("# a comment\n" + s)));
  const std::string reordered = cli_test::with(s, "name: tiny\ndimension: 2\n", "dimension: 2\nname: tiny\n");
  CHECK_FALSE(scene_difference(base, canonical(reordered)));
}

TEST_CASE("the first difference of two scenes is named by its dotted key", "[scene][checkpoint]") {
  const std::string& s = cli_test::tiny_scene;
  const std::string base = canonical(s);
  SECTION("a value") {
    const auto d = scene_difference(base, canonical(s, {"material.E=2.0e9"}));
    REQUIRE(d);
    CHECK(d->key == "material.E");
    CHECK(d->first == "1.0e9");
    CHECK(d->second == "2.0e9");
  }
  SECTION("a list item's key") {
    const auto d = scene_difference(base, canonical(s, {"boundary.1.pressure=2.0e6"}));
    REQUIRE(d);
    CHECK(d->key == "boundary.1.pressure");
  }
  SECTION("a key only one scene has") {
    const auto added = scene_difference(base, canonical(s, {"solver.max_iterations=10"}));
    REQUIRE(added);
    CHECK(added->key == "solver.max_iterations");
    CHECK(added->first == "absent");
    CHECK(added->second == "10");
    const auto removed = scene_difference(canonical(s, {"solver.max_iterations=10"}), base);
    REQUIRE(removed);
    CHECK(removed->second == "absent");
  }
  SECTION("a list of another length") {
    const auto d = scene_difference(base, canonical(s, {"probes=[{name: p, point: [0.0, 0.0], component: y}]"}));
    REQUIRE(d);
    CHECK(d->key == "probes.0.name");
    const auto shorter = scene_difference(base, canonical(cli_test::with(s, R"(  - name: mid
    line: {from: [0.005, 0.0], to: [0.005, 0.01]}
    field: stress
    component: yy
)", "")));
    REQUIRE(shorter);
    CHECK(shorter->key == "probes");
    CHECK(shorter->first == "2 items");
  }
}

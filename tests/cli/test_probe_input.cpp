// Probes that cannot read what they name are refused by key: a line that meets no particle, a
// point outside a lattice's box, a probe with both or neither of point and line.
#include "../support/cli.hpp"

using namespace cli_test;

TEST_CASE("a line probe that meets no particle names the probe", "[cli]") {
  const std::string s = with(tiny_scene, "line: {from: [0.005, 0.0], to: [0.005, 0.01]}",
                             "line: {from: [1.0, 1.0], to: [2.0, 2.0]}");
  require_rejected(s, {"probe 'mid'", "meets no particle"});
}

TEST_CASE("a 3-D line between four rows of particles names the nearest and says why it meets none", "[cli]") {
  // A bar 4 particles across: its centre line passes the four nearest rows at sqrt(2) dx / 2,
  // beyond the half spacing a line reads; before, "meets no particle" alone.
  std::string s = with(tiny_scene, "dimension: 2", "dimension: 3");
  s = with(s, "box: {min: [0.0, 0.0], max: [0.01, 0.01]}", "box: {min: [0.0, 0.0, 0.0], max: [0.01, 0.004, 0.004]}");
  s = with(s, "point: [0.005, 0.01]", "point: [0.005, 0.004, 0.002]");
  s = with(s, "line: {from: [0.005, 0.0], to: [0.005, 0.01]}", "line: {from: [0.0, 0.002, 0.002], to: [0.01, 0.002, 0.002]}");
  s = with(s, "fix: [x, y]", "fix: [x, y, z]");
  s = with(s, "component: y\n", "component: z\n");
  s = with(s, "region: top", "region: zmax");
  s = with(s, "region: bottom", "region: xmin");
  require_rejected(s, {"probes[1].line: probe 'mid' meets no particle", "within half a spacing (0.0005 m)",
                       "is 0.000707107 m from it", "move it onto a row"});
}

TEST_CASE("a point probe outside the box names the probe the distance and the face", "[cli]") {
  // tiny_scene's probe sits on the top face (0.005, 0.01): accepted (every other run here has
  // it). 1.2 spacings above it was read from the top particle (and with reconstruct, on a bar
  // in tension, extrapolated 3% high) with exit 0; half a centimetre above, the nearest
  // particle was too far and the error said "outside the body or in a hole".
  require_rejected(tiny_scene, {"probes[0].point: probe 'top_uy' lies 0.0012 m outside geometry.box (past its max y = 0.01 m)",
                                "put the point on the body's surface or inside it"},
                   "--set probes[0].point=[0.005,0.0112]");
  require_rejected(tiny_scene, {"probes[0].point: probe 'top_uy' lies 0.005 m outside geometry.box (past its max y"},
                   "--set probes[0].point=[0.005,0.015]");
  // A coordinate copied to six digits is not off the body: 5e-4 of a spacing past the face passes.
  require_valid(tiny_scene, "--set probes[0].point=[0.005,0.0100005]");
}

TEST_CASE("a probe with both point and line or neither is refused at the key it has or lacks", "[cli]") {
  require_rejected(with(tiny_scene, "    point: [0.005, 0.01]\n", ""),
                   {"probes[0].point: a probe has exactly one of point or line; this one has neither"});
  require_rejected(with(tiny_scene, "    point: [0.005, 0.01]\n", "    point: [0.005, 0.01]\n    line: {from: [0.0, 0.0], to: [0.01, 0.0]}\n"),
                   {"probes[0].line: a probe has exactly one of point or line; this one has both"});
}

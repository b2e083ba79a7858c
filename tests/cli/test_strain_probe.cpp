// The equivalent strain (probe and VTK field equivalent_strain) counts the out-of-plane
// strain of plane stress: without it a plane-stress bar in uniaxial tension read 9% low and a
// biaxial state 26% low (plane strain, whose eps_zz is 0, was right). Uniform states on a
// plate held by face rollers, which the consistent formulation reproduces exactly.
#include <cmath>

#include "../support/cli.hpp"
#include "../support/slurp.hpp"

using namespace cli_test;
using test_support::json_number;

namespace {

const std::string plate = R"(name: plate
dimension: 2
geometry: {box: {min: [0.0, 0.0], max: [0.01, 0.004]}}
discretization: {dx: 0.0005, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 200.0e9, nu: 0.3, density: 7800.0, plane: stress}
boundary:
  - {region: left, fix: [x], at: face}
  - {region: bottom, fix: [y], at: face}
  - {region: right, traction: [1.0e6, 0.0]}
solver: {type: direct}
probes:
  - {name: eqs, point: [0.005, 0.002], field: equivalent_strain}
)";

/// sqrt(2/3 e : e), e the deviator of diag(exx, eyy, ezz).
double equivalent(double exx, double eyy, double ezz) {
  const double m = (exx + eyy + ezz) / 3.0;
  return std::sqrt(2.0 / 3.0 * ((exx - m) * (exx - m) + (eyy - m) * (eyy - m) + (ezz - m) * (ezz - m)));
}

}  // namespace

TEST_CASE("the equivalent strain of plane stress counts eps_zz, plane strain has none", "[cli]") {
  const double E = 200.0e9, nu = 0.3, sx = 1.0e6, sy = 0.4e6;
  struct Case {
    const char* name;
    std::string scene;
    double expected;
  };
  const std::string biaxial = with(plate, "  - {region: right, traction: [1.0e6, 0.0]}\n",
                                   "  - {region: right, traction: [1.0e6, 0.0]}\n  - {region: top, traction: [0.0, 4.0e5]}\n");
  const Case cases[] = {
      {"plane stress, uniaxial", plate, equivalent(sx / E, -nu * sx / E, -nu * sx / E)},  // 2/3 (1 + nu) sx / E
      {"plane stress, biaxial", biaxial,
       equivalent((sx - nu * sy) / E, (sy - nu * sx) / E, -nu * (sx + sy) / E)},
      {"plane strain, uniaxial", with(plate, "plane: stress", "plane: strain"),
       equivalent((1 - nu * nu) * sx / E, -nu * (1 + nu) * sx / E, 0.0)}};
  for (const Case& c : cases) {
    INFO(c.name);
    ScratchDir dir;
    std::ofstream(dir.path / "scene.yaml") << c.scene;
    const Outcome o = perinom(dir, "run scene.yaml --out out");
    INFO(o.out << o.err);
    REQUIRE(o.exit_code == 0);
    CHECK(json_number(slurp(dir.path / "out" / "summary.json"), "eqs") == Approx(c.expected).epsilon(1e-9));
  }
}

// A small-strain answer whose displacement gradient is not small is not the body's answer:
// a modulus in the wrong unit (E = 1 Pa for 1 GPa) solved exactly, exit 0, with displacements
// ten thousand times the body's size and no word. The run now warns, naming the particle, and
// summary.json carries the largest gradient either way. Newton also reaches that answer now
// (KINSOL's default cap on a step's length stopped it with KIN_MXNEWT_5X_EXCEEDED, exit 3).
// A thin plate's deflection is checked against its thickness likewise.
#include <fstream>
#include <iterator>

#include "../support/cli.hpp"

using namespace cli_test;

namespace {

double largest_gradient(const ScratchDir& dir, const std::string& out) {
  std::ifstream in(dir.path / out / "summary.json");
  const std::string summary((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto k = summary.find("\"largest_displacement_gradient\"");
  REQUIRE(k != std::string::npos);
  const auto v = summary.find("\"value\": ", k);
  REQUIRE(v != std::string::npos);
  return std::stod(summary.substr(v + 9));
}

const std::string kWarning = "perinom: warning: the displacement gradient |grad u| reaches";

}  // namespace

TEST_CASE("a result whose displacement gradient is not small warns, by ADR and by Newton", "[cli]") {
  const std::string pascal = with(tiny_scene, "E: 1.0e9", "E: 1.0");
  const std::string newton = with(pascal, "  type: adr\n  tolerance: 1.0e-6\n  displacement_tolerance: 1.0e-6\n",
                                  "  type: newton\n");
  for (const std::string& s : {pascal, newton}) {
    ScratchDir dir;
    std::ofstream(dir.path / "scene.yaml") << s;
    const Outcome o = perinom(dir, "run scene.yaml --out out");
    INFO(o.out << o.err);
    CHECK(o.exit_code == 0);
    CHECK(o.out.find(kWarning) != std::string::npos);
    CHECK(o.out.find("at particle") != std::string::npos);
    CHECK(largest_gradient(dir, "out") > 1e3);
  }
}

TEST_CASE("a small-strain result within its range says nothing and records its largest gradient", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  const Outcome o = perinom(dir, "run scene.yaml --out out");
  INFO(o.out << o.err);
  CHECK(o.exit_code == 0);
  CHECK(o.out.find("displacement gradient") == std::string::npos);
  const double g = largest_gradient(dir, "out");
  CHECK(g > 1e-4);  // 1 MPa on 1 GPa: strains of about 1e-3
  CHECK(g < 1e-2);
}

TEST_CASE("a thin plate deflected beyond half its thickness warns, within it not", "[cli]") {
  // The clamped-plate example at 11 x 11 nodes: 1 kPa deflects it 4e-4 of its 10 mm thickness
  // at E = 210 GPa, and 400 thicknesses at E = 210 kPa (MPa taken for GPa, twice).
  ScratchDir dir;
  const std::string scene = std::string(PERINOM_SOURCE_DIR) + "/examples/thin_plate_clamped.yaml";
  const Outcome good = perinom(dir, "run " + scene + " --out good --set discretization.dx=0.05");
  INFO(good.out << good.err);
  CHECK(good.exit_code == 0);
  CHECK(good.out.find("deflection reaches") == std::string::npos);
  const Outcome bad = perinom(dir, "run " + scene + " --out bad --set discretization.dx=0.05 --set material.E=210e3");
  INFO(bad.out << bad.err);
  CHECK(bad.exit_code == 0);
  CHECK(bad.out.find("perinom: warning: the deflection reaches") != std::string::npos);
  CHECK(bad.out.find("times the plate's thickness") != std::string::npos);
  std::ifstream in(dir.path / "bad" / "summary.json");
  const std::string summary((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(summary.find("\"over_thickness\"") != std::string::npos);
}

// A run refused before its output folder is prepared: the folder a --restart resumes in
// place is left as it was.
#include <map>

#include "../support/cli.hpp"

using namespace cli_test;

namespace {

/// Every file of the folder and its bytes.
std::map<std::string, std::string> contents(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out[e.path().filename().string()] = slurp(e.path());
  return out;
}

void require_ok(const Outcome& o) {
  INFO(o.err);
  REQUIRE(o.exit_code == 0);
}

/// A 4 x 4 cloud from a point file, checkpointed every 5 iterations.
const std::string points_scene = R"(name: points
dimension: 2
geometry: {points: cloud.csv}
discretization: {dx: 0.001, horizon: {ratio: 2.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0}
model: {formulation: classical, operator_order: 1}
boundary:
  - {region: {box: {min: [0.0, 0.0], max: [0.004, 0.001]}}, fix: [x, y]}
  - {region: {box: {min: [0.0, 0.003], max: [0.004, 0.004]}}, displacement: {y: 1.0e-6}}
output: {checkpoint_every: 5}
)";

/// The cloud's text, `rows` of its 16 points, `separator` between the numbers.
std::string cloud(int rows = 16, const std::string& separator = ",") {
  std::ostringstream csv;
  csv << "x" << separator << "y" << separator << "volume\n";
  for (int k = 0; k < rows; ++k)
    csv << 0.0005 + 0.001 * (k % 4) << separator << 0.0005 + 0.001 * (k / 4) << separator << 1e-6 << "\n";
  return csv.str();
}

}  // namespace

TEST_CASE("a restart refused once the particles are built leaves the folder it resumes as it was", "[cli][checkpoint]") {
  // The counts, positions and body files are compared after the build, which came after the
  // folder was cleaned in place: a refused restart left checkpoint.bin and an error summary,
  // the finished run's snapshots and history gone.
  ScratchDir d;
  std::ofstream(d.path / "scene.yaml") << points_scene;
  std::ofstream(d.path / "cloud.csv") << cloud();
  require_ok(perinom(d, "run scene.yaml --out written"));
  const auto before = contents(d.path / "written");
  REQUIRE(before.count("points_000000.vtu"));
  REQUIRE(before.count("history.csv"));
  const std::pair<std::string, std::string> edits[] = {{"a point fewer", cloud(15)},
                                                       {"the same numbers otherwise written", cloud(16, ", ")}};
  for (const auto& [what, text] : edits) {
    INFO(what);
    std::ofstream(d.path / "cloud.csv", std::ios::trunc) << text;
    const Outcome o = perinom(d, "run scene.yaml --restart written");
    INFO(o.out << o.err);
    CHECK(o.exit_code == 2);
    CHECK(contents(d.path / "written") == before);
    // --out naming the same folder: resumed in place too, left alone.
    const Outcome other = perinom(d, "run scene.yaml --restart written --out written");
    CHECK(other.exit_code == 2);
    CHECK(contents(d.path / "written") == before);
  }
}

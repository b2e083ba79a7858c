// A run refused before its output folder is prepared (drivers/refused_run.hpp): a folder
// holding an earlier perinom run is left with a summary that says "error", never the earlier
// run's summary looking like this run's; any other folder, and the folder a --restart resumes
// in place, is left as it was.
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

/// The cloud's text, `rows` of its 16 points, `separator` between the numbers.
std::string cloud(int rows = 16, const std::string& separator = ",") {
  std::ostringstream csv;
  csv << "x" << separator << "y" << separator << "volume\n";
  for (int k = 0; k < rows; ++k)
    csv << 0.0005 + 0.001 * (k % 4) << separator << 0.0005 + 0.001 * (k / 4) << separator << 1e-6 << "\n";
  return csv.str();
}

}  // namespace

TEST_CASE("a scene refused while reading leaves an error summary where an earlier run left its results", "[cli]") {
  // A sweep read summary.json after each run: a case refused with exit 2 left the previous
  // case's "converged" summary and snapshot in the folder, and got its numbers.
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  require_ok(perinom(dir, "run scene.yaml --out out"));
  REQUIRE(fs::exists(dir.path / "out" / "tiny_000000.vtu"));
  SECTION("the summary of a finished run says error and its other files stay") {
    auto before = contents(dir.path / "out");
    require_one_clear_error(perinom(dir, "run scene.yaml --out out --set material.E=-5e9"), {"material.E"});
    const std::string summary = slurp(dir.path / "out" / "summary.json");
    CHECK(summary.find("\"status\": \"error\"") != std::string::npos);
    CHECK(summary.find("\"exit_code\": 2") != std::string::npos);
    CHECK(summary.find("material.E: must be positive") != std::string::npos);
    // A typo is no reason to lose the results: only summary.json changed (a first version
    // removed the snapshots too), and the manifest still names them for the next run.
    auto after = contents(dir.path / "out");
    before.erase("summary.json"), after.erase("summary.json");
    CHECK(after == before);
    CHECK(slurp(dir.path / "out" / "perinom.files").find("tiny_000000.vtu\n") != std::string::npos);
    require_ok(perinom(dir, "run scene.yaml --out out"));
    CHECK(slurp(dir.path / "out" / "summary.json").find("\"status\": \"converged\"") != std::string::npos);
  }
  SECTION("the default folder once the scene is read as for a memory refusal") {
    require_ok(perinom(dir, "run scene.yaml"));
    require_one_clear_error(perinom(dir, "run scene.yaml --max-memory 1K"), {"memory"});
    const std::string summary = slurp(dir.path / "out" / "tiny" / "summary.json");
    CHECK(summary.find("\"status\": \"error\"") != std::string::npos);
    CHECK(summary.find("\"name\": \"tiny\"") != std::string::npos);
  }
  SECTION("a folder no perinom run wrote is left as it was and none is created") {
    fs::create_directories(dir.path / "mine");
    std::ofstream(dir.path / "mine" / "summary.json") << "mine";
    require_one_clear_error(perinom(dir, "run scene.yaml --out mine --set material.E=-5e9"), {"material.E"});
    CHECK(contents(dir.path / "mine") == std::map<std::string, std::string>{{"summary.json", "mine"}});
    require_one_clear_error(perinom(dir, "run scene.yaml --out fresh --set material.E=-5e9"), {"material.E"});
    CHECK_FALSE(fs::exists(dir.path / "fresh"));
  }
}

TEST_CASE("a restart refused once the particles are built leaves the folder it resumes as it was", "[cli][checkpoint]") {
  // The counts, positions and body files are compared after the build, which came after the
  // folder was cleaned in place: a refused restart left checkpoint.bin and an error summary,
  // the finished run's snapshots and history gone.
  ScratchDir d;
  std::ofstream(d.path / "scene.yaml") << point_file_scene;
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
  // Into another folder that holds an earlier run: its summary says error.
  std::ofstream(d.path / "cloud.csv", std::ios::trunc) << cloud();
  require_ok(perinom(d, "run scene.yaml --out other"));
  std::ofstream(d.path / "cloud.csv", std::ios::trunc) << cloud(15);
  CHECK(perinom(d, "run scene.yaml --restart written --out other").exit_code == 2);
  CHECK(slurp(d.path / "other" / "summary.json").find("\"status\": \"error\"") != std::string::npos);
  CHECK(contents(d.path / "written") == before);
}

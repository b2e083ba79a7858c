// `perinom run` on a plastic scene: the step table's files, the probe histories, the plastic
// VTK fields and CSV snapshots, the Newton check of a load path, and the table a killed
// path leaves.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <signal.h>
#include <unistd.h>

#include "../support/background_run.hpp"
#include "../support/slurp.hpp"

namespace fs = std::filesystem;

namespace {

using test_support::json_number;
using test_support::kill_when;
using test_support::slurp;
using test_support::start_in_background;

std::size_t lines(const fs::path& p) {
  const std::string s = slurp(p);
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

/// Runs `perinom run` on the biaxial example in a fresh folder `d` with the given --set
/// overrides (stdout in d/out.txt, stderr in d/err.txt) and requires exit code 0.
void run_biaxial(const fs::path& d, const std::string& sets) {
  fs::remove_all(d);
  fs::create_directories(d);
  const std::string cmd = "cd '" + d.string() + "' && '" PERINOM_EXE "' run '" PERINOM_SOURCE_DIR
                          "/examples/biaxial_compression.yaml' --out out " + sets + " >out.txt 2>err.txt";
  const int status = std::system(cmd.c_str());
  REQUIRE(WIFEXITED(status));
  INFO(slurp(d / "err.txt"));
  REQUIRE(WEXITSTATUS(status) == 0);
}

/// Starts `perinom run` on the biaxial example in a fresh folder `d` (output in d/out, stdout
/// in d/out.txt) with the given --set overrides, in the background: its process id.
pid_t start_biaxial(const fs::path& d, const std::string& sets) {
  fs::remove_all(d);
  fs::create_directories(d);
  return start_in_background(d, "'" PERINOM_EXE "' run '" PERINOM_SOURCE_DIR "/examples/biaxial_compression.yaml' "
                                "--out out --threads 1 " + sets + " >out.txt 2>&1");
}

}  // namespace

TEST_CASE("a plastic scene writes its step table, probe histories and plastic fields", "[cli][load_path]") {
  const fs::path d = fs::temp_directory_path() / "perinom_load_path_run";
  run_biaxial(d, "--set stages.0.steps=5 --set stages.1.steps=5 --set solver.check=newton --set output.csv=true "
                 "--set output.vtk_every=5 --set material.h=50");
  const fs::path out = d / "out";
  CHECK(lines(out / "load_steps.csv") == 1 + 10);
  // The example's snapshots after steps 100 and 200 lie beyond the shortened path: said.
  CHECK(slurp(d / "out.txt").find("warning: output.vtk_steps: load step(s) 100, 200 beyond the path's 10: no "
                                  "snapshot there") != std::string::npos);
  // Each step's reactions: the scene's supports and the compression stage's own.
  CHECK(slurp(out / "load_steps.csv").find(",seconds,boundary.0.Rx,boundary.0.Ry,boundary.1.Rx,boundary.1.Ry,"
                                           "stages.1.boundary.1.Rx,stages.1.boundary.1.Ry\n") != std::string::npos);
  CHECK(lines(out / "probe_center_von_mises_history.csv") == 1 + 10);
  CHECK(lines(out / "probe_center_eq_plastic_strain_history.csv") == 1 + 10);
  // One name per column (a von_mises probe's own column was named von_mises twice).
  CHECK(slurp(out / "probe_center_von_mises_history.csv")
            .rfind("stage,step,load_factor,value,von_mises,mean_stress,equivalent_strain,eq_plastic_strain\n", 0) == 0);
  const std::string summary = slurp(out / "summary.json");
  CHECK(summary.find("\"load_steps\": 10") != std::string::npos);
  CHECK(summary.find("\"particles_yielded\": 400") != std::string::npos);
  CHECK(summary.find("\"probe_histories_relative_max\"") != std::string::npos);
  CHECK(summary.find("\"newton_converged\": true") != std::string::npos);
  CHECK(summary.find("\"equilibrium\"") != std::string::npos);
  // The VTK point data of a plastic scene, and the same as CSV (snapshots after steps 5, 10).
  const std::string vtu = slurp(out / "biaxial_compression_000000.vtu");
  for (const char* field : {"eq_plastic_strain", "plastic_strain", "yielded", "mean_stress", "von_mises"}) {
    INFO(field);
    CHECK(vtu.find(std::string("Name=\"") + field + "\"") != std::string::npos);
  }
  const std::string csv = slurp(out / "biaxial_compression_000001.csv");
  CHECK(csv.rfind("x,y,z,displacement_0", 0) == 0);
  CHECK(csv.find("eq_plastic_strain") != std::string::npos);
  CHECK(lines(out / "biaxial_compression_000001.csv") == 1 + 400);
  // The step table on stdout names the columns.
  CHECK(slurp(d / "out.txt").find("rounds  flagged yielding") != std::string::npos);
  CHECK(slurp(d / "out.txt").find("follower") == std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("plain ADR on a Drucker-Prager path warns that it yields falsely, LBC does not", "[cli][load_path]") {
  // In 1 + 1 load steps at dx = 6.25 mm the biaxial example's centre read 161 kPa von Mises by
  // plain ADR against 228 kPa by LBC and Newton (on the yield surface), exit 0 and no word.
  const fs::path d = fs::temp_directory_path() / "perinom_load_path_plain_adr";
  const std::string sets = "--set discretization.dx=0.00625 --set stages.0.steps=1 --set stages.1.steps=1";
  run_biaxial(d, sets + " --set solver.type=adr");
  const std::string said = "perinom: warning: solver.type adr with material drucker_prager: plain ADR commits";
  CHECK(slurp(d / "out.txt").find(said) != std::string::npos);
  CHECK(slurp(d / "out" / "summary.json").find("solver.type adr with material drucker_prager") != std::string::npos);
  CHECK(json_number(slurp(d / "out" / "summary.json"), "center_von_mises") == Approx(161392).epsilon(1e-3));
  run_biaxial(d, sets);
  CHECK(slurp(d / "out.txt").find("plain ADR commits") == std::string::npos);
  CHECK(json_number(slurp(d / "out" / "summary.json"), "center_von_mises") == Approx(228265).epsilon(1e-4));
  fs::remove_all(d);
}

TEST_CASE("finite rotation says how its pressures act, and its Newton check follows LBC", "[cli][load_path]") {
  // The check re-solves with Newton on a model whose follower loads LBC has already set.
  const fs::path d = fs::temp_directory_path() / "perinom_load_path_follower";
  for (const bool follower : {true, false}) {
    run_biaxial(d, std::string("--set stages.0.steps=2 --set stages.1.steps=2 --set model.kinematics=finite_rotation "
                               "--set material.h=50 --set solver.check=newton") +
                       (follower ? "" : " --set model.follower_pressure=false"));
    const std::string out = slurp(d / "out.txt");
    CHECK((out.find("pressures follow the deformed surface") != std::string::npos) == follower);
    CHECK((out.find("tractions and pressures stay nominal") != std::string::npos) == !follower);
    CHECK(slurp(d / "out" / "summary.json").find("\"newton_converged\": true") != std::string::npos);
    CHECK(slurp(d / "out" / "summary.json").find("unstable_end") == std::string::npos);  // rollers hold it
  }
  fs::remove_all(d);
}

TEST_CASE("a path that converges on an unstable state under dead pressures warns and says so in the summary", "[cli][load_path]") {
  // A block pressed by dead pressures, held at its centre and at one point against turning:
  // the loads' moment once turned outweighs what two held particles resist, and the balanced,
  // symmetric state is unstable (exit 0 with nothing said before).
  const fs::path d = fs::temp_directory_path() / "perinom_load_path_unstable_end";
  fs::create_directories(d);
  std::ofstream(d / "pressed.yaml") << R"(name: pressed
dimension: 2
geometry: {box: {min: [0.0, 0.0], max: [0.022, 0.022]}}
discretization: {dx: 0.002, horizon: {ratio: 3.015}}
material: {type: drucker_prager, E: 30.0e6, nu: 0.25, density: 2000.0, plane: strain, friction_angle: 30.0,
           cohesion: 1.0e12, m0: 0.5, h: 50.0}
model: {type: correspondence, formulation: consistent, kinematics: finite_rotation, follower_pressure: false}
boundary:
  - {region: {point: [0.011, 0.011]}, fix: [x, y]}
  - {region: {point: [0.019, 0.011]}, fix: [y]}
  - {region: left, pressure: 200.0e3}
  - {region: right, pressure: 200.0e3}
  - {region: top, pressure: 600.0e3}
  - {region: bottom, pressure: 600.0e3}
stages:
  - {name: press, steps: 2}
solver: {type: lbc, tolerance: 1.0e-9}
)";
  const std::string cmd = "cd '" + d.string() + "' && '" PERINOM_EXE "' run pressed.yaml --out out >out.txt 2>&1";
  const int status = std::system(cmd.c_str());
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  INFO(slurp(d / "out.txt"));
  CHECK(slurp(d / "out.txt").find("perinom: warning: the converged end state is an unstable equilibrium: its stiffness "
                                  "gives way (x^T K x < 0) along 1 independent direction") != std::string::npos);
  CHECK(slurp(d / "out" / "summary.json").find("\"unstable_end\": \"an unstable equilibrium") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("a killed load path leaves its step table and probe history, whole rows only", "[cli][load_path]") {
  // A long path (100,000 steps) killed soon after its first step: the tables are there, a
  // few steps long, every row complete, beside the marker of an unfinished run.
  const fs::path d = fs::temp_directory_path() / "perinom_killed_load_path";
  const pid_t pid = start_biaxial(d, "--set stages.0.steps=100000");
  const fs::path table = d / "out" / "load_steps.csv";
  kill_when(pid, 60.0, [&] { return fs::exists(table); });
  REQUIRE(fs::exists(table));
  CHECK(fs::exists(d / "out" / "run.incomplete"));
  for (const fs::path& f : {table, d / "out" / "probe_center_von_mises_history.csv"}) {
    INFO(f.string());
    const std::string s = slurp(f);
    std::istringstream in(s);
    std::string header, row;
    std::getline(in, header);
    const auto commas = std::count(header.begin(), header.end(), ',');
    std::size_t rows = 0;
    while (std::getline(in, row)) {
      CHECK(std::count(row.begin(), row.end(), ',') == commas);
      ++rows;
    }
    CHECK(s.back() == '\n');
    CHECK(rows >= 1);
    CHECK(rows < 100000);
  }
  fs::remove_all(d);
}

TEST_CASE("a load step that takes long says it is still balancing", "[cli][load_path]") {
  // A first step that cannot converge (tolerance 1e-300): after 10 s a line says where it is.
  const fs::path d = fs::temp_directory_path() / "perinom_long_load_step";
  const pid_t pid = start_biaxial(d, "--set stages.0.steps=1 --set solver.tolerance=1e-300 "
                                     "--set solver.displacement_tolerance=1e-300 --set solver.max_iterations=1000000000");
  const auto said = [&] { return slurp(d / "out.txt").find("still balancing") != std::string::npos; };
  kill_when(pid, 60.0, said);
  INFO(slurp(d / "out.txt"));
  CHECK(said());
  CHECK(slurp(d / "out.txt").find("load step 1/101 still balancing: ") != std::string::npos);
  fs::remove_all(d);
}

// Verlet's energy-balance guard as a user meets it, on the vibrating bar of the examples:
// the improved formulation (allowed by solver.allow_unstable) is stopped with exit code 3,
// the symmetric ones run their 4000 steps conserving energy. Each test runs the real binary
// in its own temporary folder.
#include <catch2/catch.hpp>

#include "../support/bar_run.hpp"
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using bar_test::bar;
using bar_test::Outcome;

/// history.csv's rows (step, time, kinetic, strain, external work, total).
std::vector<std::vector<double>> history(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST_CASE("Verlet with the improved formulation is stopped by the energy balance long before its 4000 steps", "[cli][verlet]") {
  // Issue 14: without the guard this run ends with 1e166 J of energy and exit 0.
  const Outcome o = bar("verlet_improved", "run", "--out out --set model.formulation=improved --set solver.allow_unstable=true");
  INFO(o.out << o.err);
  CHECK(o.exit_code == 3);
  CHECK(o.err.find("energy balance failed at step") != std::string::npos);
  const auto rows = history(o.dir / "out" / "history.csv");
  REQUIRE(!rows.empty());
  CHECK(rows.back()[0] < 2000);
  // The run stopped while the energy was still finite and small.
  CHECK(rows.back()[2] + rows.back()[3] < 1.0);
}

TEST_CASE("Verlet with the consistent and classical formulations conserves energy on the vibrating bar", "[cli][verlet]") {
  // Held at the particles and at the face (Galerkin): the face constraints read each other
  // and must hold exactly at every step; with one Gauss-Seidel sweep a step they lagged, and
  // the consistent bar gained energy until the guard stopped it at step 3840 (exit 3).
  for (const std::string f : {"consistent", "classical", "consistent --set boundary.0.at=face",
                              "classical --set boundary.0.at=face"}) {
    std::string name = "verlet_" + f.substr(0, f.find(' ')) + (f.find("face") != std::string::npos ? "_face" : "");
    const Outcome o = bar(name, "run", "--out out --set model.formulation=" + f);
    INFO(f << ": " << o.out << o.err);
    REQUIRE(o.exit_code == 0);
    CHECK(o.err.empty());
    const auto rows = history(o.dir / "out" / "history.csv");
    REQUIRE(rows.size() == 201);  // 4000 steps, a row every 20
    double defect = 0.0, work = 0.0;
    for (const auto& r : rows) defect = std::max(defect, std::abs(r[5])), work = std::max(work, r[4]);
    WARN(f << ": max |kinetic + strain - external work| = " << defect << " J, max external work " << work
           << " J, ratio " << defect / work);
    CHECK(work > 0.0);
    CHECK(defect < 1e-3 * work);
  }
}

TEST_CASE("a Verlet run that diverges with a given dt above the stable step estimate says so", "[cli][verlet]") {
  // solver.dt = 1 s on the bar (estimate about 1.6e-7 s): NaN by step 11, and the message
  // said nothing of the step; 3e-7 s (1.9 times the estimate) is stopped by the energy guard.
  for (const std::string dt : {"1.0", "3.0e-7"}) {
    const Outcome o = bar("verlet_dt_" + dt, "run", "--out out --set solver.dt=" + dt);
    INFO(dt << ": " << o.out << o.err);
    CHECK(o.exit_code == 3);
    CHECK(o.err.find("times the stable step estimate") != std::string::npos);
    CHECK(o.err.find("solver.dt = ") != std::string::npos);
  }
  const Outcome fine = bar("verlet_dt_fine", "run", "--out out --set solver.dt=1.0e-7 --set solver.steps=200");
  INFO(fine.out << fine.err);
  CHECK(fine.exit_code == 0);
  CHECK(fine.out.find("stable step estimate") == std::string::npos);
  // Above the estimate (a lower bound) but below the true limit: warned before the steps, and it runs.
  const Outcome bold = bar("verlet_dt_bold", "run", "--out out --set solver.dt=1.7e-7 --set solver.steps=2000");
  INFO(bold.out << bold.err);
  CHECK(bold.exit_code == 0);
  const auto warned = bold.out.find("perinom: warning: solver.dt = 1.7e-07 s is 1.");
  CHECK(warned != std::string::npos);
  CHECK(warned < bold.out.find("results in"));
}

TEST_CASE("a Verlet run whose stable step is 0 is refused by the key that made it, never a success", "[cli][verlet]") {
  // A density of 1e-300 made the stable step 0: "100 steps to t = 0 s", exit 0.
  const Outcome o = bar("zero_step", "run", "--out out --set material.density=1e-300 --set solver.steps=100");
  INFO(o.out << o.err);
  CHECK(o.exit_code == 2);
  CHECK(o.err.find("perinom: error: ") == 0);
  CHECK(o.err.find("material.density = 1e-300 kg/m^3") != std::string::npos);
  CHECK(o.err.find("no step to integrate with") != std::string::npos);
  CHECK(o.out.find("steps to t =") == std::string::npos);
}

TEST_CASE("a Verlet run that ends before its ramp_time says how far its loads got", "[cli][verlet]") {
  // 100 steps of about 1.5e-7 s against a ramp of 1e-4 s: the loads reach about 15%.
  const Outcome o = bar("ramp", "run", "--out out --set solver.steps=100 --set solver.ramp_time=1.0e-4");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  REQUIRE(o.exit_code == 0);
  CHECK(o.out.find("before solver.ramp_time = 1.0000e-04 s: the loads reached") != std::string::npos);
  const std::string summary = test_support::slurp(o.dir / "out" / "summary.json");
  const double reached = test_support::json_number(summary, "load_factor_at_end");
  CHECK(reached > 0.05);
  CHECK(reached < 0.5);
  CHECK(reached == Approx(test_support::json_number(summary, "end_time") / 1.0e-4).epsilon(1e-9));
  // A ramp the run outlasts: the factor 1, no warning.
  const Outcome whole = bar("ramp_whole", "run", "--out out --set solver.steps=100 --set solver.ramp_time=1.0e-6");
  REQUIRE(whole.exit_code == 0);
  CHECK(whole.out.find("the loads reached") == std::string::npos);
  CHECK(test_support::json_number(test_support::slurp(whole.dir / "out" / "summary.json"), "load_factor_at_end") == 1.0);
}

TEST_CASE("a Verlet history ends at the last step, whatever history_every", "[cli][verlet]") {
  // 35 steps at history_every 10 ended the history at step 30.
  const Outcome o = bar("last_row", "run", "--out out --set solver.steps=35 --set solver.history_every=10");
  INFO("stderr: " << o.err);
  REQUIRE(o.exit_code == 0);
  const auto rows = history(o.dir / "out" / "history.csv");
  REQUIRE(rows.size() == 5);  // steps 0, 10, 20, 30 and 35
  CHECK(rows.back()[0] == 35.0);
  CHECK(rows[3][0] == 30.0);
}

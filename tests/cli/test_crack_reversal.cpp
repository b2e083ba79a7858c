// A softening crack under reversed load (issue 18, damage.fracture_energy): the band bar of
// test_quasi_static_fracture.cpp pulled past its peak, pushed back until the closed crack
// carries compression, then pulled apart. The crack unloads to the origin without dissipating,
// its closed faces carry compression (closed softening bonds push back, CohesiveBonds::force),
// and opened again it rejoins the path of a bar pulled once.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "../support/cli.hpp"
#include "../support/step_table.hpp"

using namespace cli_test;

namespace {

/// examples/brittle_bar.yaml with its stages replaced by `stages`, every step 0.5 um of the
/// pulled end, and the band of test_quasi_static_fracture.cpp (bonds break only within 6.5 mm
/// of mid-length, G_f = 50 N/m).
std::string band_bar(const std::string& stages) {
  const std::string example = slurp(PERINOM_SOURCE_DIR "/examples/brittle_bar.yaml");
  const auto from = example.find("stages:"), to = example.find("solver:");
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  return example.substr(0, from) + "stages:\n" + stages + example.substr(to);
}

std::string stage(const std::string& name, int steps, double dx) {
  return "  - name: " + name + "\n    steps: " + std::to_string(steps) +
         "\n    boundary:\n      - {region: right, displacement: {x: " + std::to_string(dx) +
         "}}\n      - {region: {point: [0.1, 0.0]}, fix: [y]}\n";
}

const std::string band = " --set damage.fracture_energy=50 --set 'damage.no_fail.0.region.box.max=[0.0435, 1.0]'"
                         " --set 'damage.no_fail.1.region.box.min=[0.0565, -1.0]'";

/// The run's step table, with the pulled end's displacement u (um) and reaction R (N) per step.
struct Path {
  std::map<std::string, std::vector<double>> t;
  std::vector<double> u, R;
};

Path run(const ScratchDir& d, const std::string& stages, const std::vector<double>& step_um) {
  std::ofstream(d.path / "scene.yaml") << band_bar(stages);
  const Outcome o = perinom(d, "run scene.yaml --out out" + band);
  INFO(o.out << o.err);
  REQUIRE(o.exit_code == 0);
  Path p;
  p.t = columns(slurp(d.path / "out" / "load_steps.csv"));
  double u = 0.0;
  for (std::size_t k = 0; k < p.t.at("stage").size(); ++k) {
    const int s = int(p.t.at("stage")[k]) - 1;
    u += step_um.at(std::size_t(s));
    p.u.push_back(u);
    p.R.push_back(p.t.at("stages." + std::to_string(s) + ".boundary.0.Rx")[k]);
  }
  return p;
}

}  // namespace

TEST_CASE("a softening crack unloads to the origin, carries compression closed and, opened again, rejoins its path",
          "[cli][fracture][load_path]") {
  // Pulled to 40 um (past the peak at 7 um, softening), pushed to -20 um (about 5 f_t A of
  // compression), pulled to 300 um (past eta_u = 79 um: parted). Measured at dx = 2 mm: the
  // unloading is linear to the origin (R/u within 1e-5); the closed crack's stiffness is 0.927
  // of the intact bar's (the band's pairwise bonds, not the correspondence model; 0.931 at dx =
  // 1 mm; a closed softening bond carried nothing before 2026-12-05, and the bar nothing in
  // compression); nothing is dissipated before 1.96 f_t A of compression (2.20 at dx = 1 mm);
  // beyond it the band's bonds along the crack, stretched sideways by the squeezed band,
  // soften: 0.45% of G_f A by -20 um (0.56% at dx = 1 mm), docs/theory.md "Softening bonds".
  // Opened again, past 41 um the reaction is the once-pulled bar's within 0.02%.
  ScratchDir reversed, once;
  const Path p = run(reversed, stage("pull", 80, 4.0e-5) + stage("push", 120, -6.0e-5) + stage("reopen", 640, 3.2e-4),
                     {0.5, -0.5, 0.5});
  const Path m = run(once, stage("pull", 600, 3.0e-4), {0.5});
  REQUIRE(p.R.size() == 840);
  REQUIRE(m.R.size() == 600);
  const double f_t_A = 1.0e6 * 0.02 * 0.01, G_f_A = 50.0 * 0.02 * 0.01;
  const std::vector<double>& D = p.t.at("dissipated_energy");
  for (const double r : p.t.at("residual")) CHECK(r <= 1e-8);

  // Unloading (steps 80-158: u from 39.5 to 0.5 um): R/u constant, nothing dissipated.
  const double secant = p.R[79] / p.u[79];
  for (std::size_t k = 80; k < 159; ++k) {
    CHECK(p.R[k] / p.u[k] == Approx(secant).epsilon(1e-3));
    CHECK(std::abs(D[k] - D[79]) < 1e-6 * G_f_A);
  }
  // Closed (u < 0): compression, at a stiffness near the intact bar's, and up to 1.5 f_t A
  // nothing dissipated.
  const double intact = m.R[4] / m.u[4];
  std::size_t k = 160;
  for (; k < 200 && p.R[k] > -1.5 * f_t_A; ++k) CHECK(std::abs(D[k] - D[79]) < 1e-6 * G_f_A);
  REQUIRE(k < 200);  // (without the contact the closed crack carried nothing: 0 N at -20 um)
  const double closed = (p.R[k] - p.R[161]) / (p.u[k] - p.u[161]);
  CHECK(closed / intact > 0.9);
  CHECK(closed / intact < 1.0);
  CHECK(D[199] - D[79] < 0.01 * G_f_A);
  // Opened again: the once-pulled bar's reaction from 41 um (one step past the last opening)
  // to 120 um, where the crack has parted.
  std::size_t checked = 0;
  for (std::size_t j = 200; j < p.R.size(); ++j) {
    if (p.u[j] < 40.75 || p.u[j] > 120.25) continue;
    const std::size_t i = std::size_t(std::lround(p.u[j] / 0.5)) - 1;
    REQUIRE(std::abs(m.u[i] - p.u[j]) < 1e-9);
    CHECK(p.R[j] == Approx(m.R[i]).epsilon(0.005));
    ++checked;
  }
  CHECK(checked == 159);
  // Parted: nothing carried, and the energy account the once-pulled bar's, plus what the
  // compression dissipated.
  CHECK(std::abs(p.R.back()) < 1e-6 * f_t_A);
  CHECK(D.back() / G_f_A == Approx(1.0).margin(0.05));
  CHECK(D.back() - m.t.at("dissipated_energy").back() == Approx(D[199] - D[79]).margin(1e-3 * G_f_A));
}

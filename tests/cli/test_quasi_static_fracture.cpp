// Bonds breaking on a load path (issue 18): each load step a fixed point of balance and
// breaking. A brittle bar under displacement control carries f_t times its section, fails
// within one load step and carries nothing after it; without grips its ends break first, in
// a cascade of balances within the step; the energy its break dissipates is what it stored;
// a plastic bar breaks when its plastic stress reaches f_t; a cap on the balances stops the run, saying so; a step
// that cannot balance because a crack freed a piece names it and says how much of its
// residual sits on the detached particles; the Newton check solves a broken beam at its final
// damage state.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "../support/cli.hpp"
#include "../support/step_table.hpp"

using namespace cli_test;

namespace {

const std::string bar = "'" PERINOM_SOURCE_DIR "/examples/brittle_bar.yaml'";

/// The bar run with `extra` options: its outcome and, when it ran through, its step table,
/// with the pulled end's reaction, the broken bonds and the peak step at hand.
struct BarRun {
  Outcome o;
  std::map<std::string, std::vector<double>> t;
  std::vector<double> R, broken;
  std::size_t peak = 0;
};

BarRun run_bar(const ScratchDir& d, const std::string& extra, const std::string& scene = bar) {
  BarRun b;
  b.o = perinom(d, "run " + scene + " --out out " + extra);
  if (b.o.exit_code != 0) return b;
  b.t = columns(slurp(d.path / "out" / "load_steps.csv"));
  b.R = b.t["stages.0.boundary.2.Rx"], b.broken = b.t["broken_bonds"];
  b.peak = std::size_t(std::max_element(b.R.begin(), b.R.end()) - b.R.begin());
  return b;
}

/// A bar with grips fails as the stress criterion says: the peak reaction is f_t A within 1%
/// and never above it (no bond survives a stress above f_t; a load step is under 1% of it),
/// nothing breaks before the failing step, which breaks every bond between the grips (the
/// stress is uniform there), the pieces carry nothing after it, and every step balanced
/// (after the break against the load carried before it).
void check_fails_at_f_t_A(const BarRun& b) {
  const auto &R = b.R, &broken = b.broken;
  const std::size_t peak = b.peak;
  const double carried = 1.0e6 * 0.02 * 0.01;  // f_t times the section (N)
  CHECK(R[peak] <= carried * (1.0 + 1e-9));
  CHECK(R[peak] >= 0.99 * carried);
  REQUIRE(peak + 1 < R.size());
  for (std::size_t k = 0; k <= peak; ++k) CHECK(broken[k] == 0.0);
  CHECK(broken[peak + 1] > 4000.0);
  for (std::size_t k = peak + 1; k < R.size(); ++k) CHECK(std::abs(R[k]) < 1e-6 * R[peak]);
  for (std::size_t k = peak + 2; k < R.size(); ++k) CHECK(broken[k] == 0.0);
  for (const double r : b.t.at("residual")) CHECK(r <= 1e-8);
}

}  // namespace

TEST_CASE("with fracture_energy a bar cracking in a band dissipates G_f times its section, then carries nothing",
          "[cli][fracture][load_path]") {
  // Only the bonds within a band 13 mm wide at mid-length may break (every bond crossing its
  // middle does), G_f = 50 N/m: the pulled end goes 0.3 mm in 600 steps, past eta_u = pi G_f /
  // (2 f_t) = 79 um of opening. The energy account (load_steps.csv dissipated_energy, W - E)
  // at the end against G_f A = 0.01 J: measured 1.022 (the lattice crossing the law's scaling
  // assumes, 1.007 by a count, the brittle energy released when bonds break, and the
  // trapezoid of the softening steps). The peak: the band breaks at 195 N (load step 8), then
  // its softening bonds carry up to 210.8 N (step 14) against f_t A = 200 N, 1.054 f_t A
  // (1.025 at dx = 1 mm, docs/theory.md). Before closed bonds pushed back (2026-12-05) the
  // band's detached particles collapsed sideways and the peak was the break's 194 N (0.77
  // f_t A at dx = 1 mm).
  ScratchDir d;
  const std::string band = " --set damage.fracture_energy=50 --set 'damage.no_fail.0.region.box.max=[0.0435, 1.0]'"
                           " --set 'damage.no_fail.1.region.box.min=[0.0565, -1.0]' --set stages.0.steps=600"
                           " --set stages.0.boundary.2.displacement.x=3.0e-4";
  const BarRun b = run_bar(d, band);
  INFO(b.o.out << b.o.err);
  REQUIRE(b.o.exit_code == 0);
  REQUIRE(b.R.size() == 600);
  const double carried = 1.0e6 * 0.02 * 0.01, G_f_A = 50.0 * 0.02 * 0.01;
  CHECK(b.R[b.peak] >= 0.95 * carried);
  CHECK(b.R[b.peak] <= 1.06 * carried);  // (at most f_t A while the band collapsed: see above)
  // It softens: at 40 um (ten times the displacement at f_t A) it carries less than at the
  // peak, and more than half of it (the plain criterion drops to zero within one step).
  CHECK(b.peak < 79);
  CHECK(b.R[79] < 0.9 * b.R[b.peak]);
  CHECK(b.R[79] > 0.5 * b.R[b.peak]);
  CHECK(std::abs(b.R.back()) < 1e-6 * b.R[b.peak]);
  const double D = b.t.at("dissipated_energy").back();
  CHECK(D / G_f_A == Approx(1.0).margin(0.05));
  for (const double r : b.t.at("residual")) CHECK(r <= 1e-8);
  // The bonds across the crack have opened past eta_u by the end, the others in the band not:
  // the summary counts them. A plane between two particle columns is crossed by 162 bonds.
  const std::string summary = slurp(d.path / "out" / "summary.json");
  const auto at = summary.find("\"softening_bonds_spent\": ");
  REQUIRE(at != std::string::npos);
  const auto broke = summary.find("\"bonds_broken\": ");
  REQUIRE(broke != std::string::npos);
  const long spent = std::stol(summary.substr(at + 25)), broken = std::stol(summary.substr(broke + 16));
  CHECK(spent >= 162);
  CHECK(spent < broken);
  // The regularisation is partial (a notch tip's peak still moves with the spacing): said at the start.
  CHECK(b.o.out.find("perinom: note: damage.fracture_energy: the broken bonds dissipate G_f") != std::string::npos);
}

TEST_CASE("a brittle bar under displacement control carries f_t A, then nothing, failing within one load step",
          "[cli][fracture][load_path]") {
  ScratchDir d;
  const BarRun b = run_bar(d, "");
  INFO(b.o.out << b.o.err);
  REQUIRE(b.o.exit_code == 0);
  REQUIRE(b.R.size() == 200);
  REQUIRE(b.broken.size() == 200);
  check_fails_at_f_t_A(b);  // a load step is 0.84% of f_t A (measured 0.40% below)
  // The energy account. Up to the break the work of the internal forces over every dof is the
  // pulled end's reaction times its displacement (the trapezoid of the table); after it the
  // energy the bar stored at the breaking step's first balance, 0.5 k u_b^2 with k the intact
  // stiffness, is all dissipated (the pieces store nothing).
  const auto &s = b.t.at("load_factor"), &W = b.t.at("external_work"), &D = b.t.at("dissipated_energy");
  const double pull = 6.0e-6;  // the end's displacement at the stage's end (m)
  double work = 0.0;
  for (std::size_t k = 0; k <= b.peak; ++k) {
    work += 0.5 * (b.R[k] + (k ? b.R[k - 1] : 0.0)) * pull * (s[k] - (k ? s[k - 1] : 0.0));
    CHECK(D[k] == 0.0);
  }
  // Both agree to the balances' tolerance (1e-8 here): measured 3e-14 and 2.8e-9 in the
  // Release build, 4.9e-10 and 9.5e-10 in the sanitized one (other iterates).
  CHECK(W[b.peak] == Approx(work).epsilon(1e-7));
  const double u_b = pull * s[b.peak + 1];
  const double stored = 0.5 * b.R[b.peak] / (pull * s[b.peak]) * u_b * u_b;
  CHECK(D.back() == Approx(stored).epsilon(1e-7));
  CHECK(W.back() == Approx(D.back()).epsilon(1e-9));
  CHECK(slurp(d.path / "out" / "summary.json").find("\"bonds_broken\": ") != std::string::npos);
  CHECK(b.o.out.find("   broken") != std::string::npos);  // the step table's column
}

TEST_CASE("without grips the bar breaks next to its ends, in a cascade of balances within one step",
          "[cli][fracture][load_path]") {
  // Next to a held end the classical formulation's stress is above the interior's: the first
  // bonds break there, and each break raises the stress beside it at the same load. The step
  // balances again until nothing more is due (4 balances measured); bonds left across the
  // damaged bands still carry 13% of the peak (the criterion reads each end's stress, which
  // is low on a particle whose family the crack has cut).
  ScratchDir d;
  const BarRun b = run_bar(d, "--set 'damage.no_fail=[]'");
  INFO(b.o.out << b.o.err);
  REQUIRE(b.o.exit_code == 0);
  const auto &R = b.R, &broken = b.broken;
  const std::size_t peak = b.peak;
  REQUIRE(peak + 1 < R.size());
  CHECK(R[peak] < 0.99 * 200.0);  // measured 2.1% below f_t A
  CHECK(R[peak] > 0.95 * 200.0);
  CHECK(broken[peak + 1] > 500.0);
  CHECK(b.t.at("rounds")[peak + 1] >= 3.0);
  CHECK(broken[peak + 2] == 0.0);  // the fixed point held: nothing left due one step on
  CHECK(R[peak + 1] < 0.2 * R[peak]);
}

TEST_CASE("a Drucker-Prager bar yields, hardens and breaks when its plastic stress reaches f_t",
          "[cli][fracture][load_path][plasticity]") {
  // The bar in plane strain with Drucker-Prager (phi = 30 deg, c = 1.5 MPa, m0 = 0.2, h =
  // 20000): it yields near 0.65 MPa, hardens, and its bonds break when the stress of the
  // plastic state reaches f_t = 1 MPa, at a larger stretch than an elastic bar's. A criterion
  // that read the elastic stress of grad u would break it near 174 N (step 60).
  ScratchDir d;
  const std::string scene = with(with(with(slurp(PERINOM_SOURCE_DIR "/examples/brittle_bar.yaml"),
                                     "material: {type: linear_elastic, E: 27.0e9, nu: 0.18, density: 2400.0, plane: stress}",
                                     "material: {type: drucker_prager, E: 27.0e9, nu: 0.18, density: 2400.0, plane: strain, "
                                     "friction_angle: 30.0, cohesion: 1.5e6, m0: 0.2, h: 20000.0}"),
                                "solver: {type: adr,", "solver: {type: lbc,"),
                           "x: 6.0e-6", "x: 1.2e-5");
  std::ofstream(d.path / "dp_bar.yaml") << scene;
  const BarRun b = run_bar(d, "", "dp_bar.yaml");
  INFO(b.o.out << b.o.err);
  REQUIRE(b.o.exit_code == 0);
  check_fails_at_f_t_A(b);  // measured 0.61% below f_t A
  CHECK(b.t.at("plastic")[b.peak] > 0.0);  // it yielded before it broke
  // Elastic until yield: the first steps' slope; an elastic bar would carry f_t A at step
  // f_t A / slope (60); the plastic one breaks later (75 measured).
  const double slope = b.R[9] / 10.0;
  CHECK(double(b.peak + 1) > 1.15 * 200.0 / slope);
}

TEST_CASE("a load step whose bonds go on breaking past solver.max_rounds stops the run, saying so",
          "[cli][fracture][load_path]") {
  ScratchDir d;
  const Outcome o = run_bar(d, "--set 'damage.no_fail=[]' --set solver.max_rounds=2").o;
  INFO(o.out << o.err);
  CHECK(o.exit_code == 1);  // not converged, as when a balance runs out of iterations
  CHECK(o.err.find("load step 118: bonds still breaking after 2 balances (solver.max_rounds)") != std::string::npos);
  const std::string summary = slurp(d.path / "out" / "summary.json");
  CHECK(summary.find("\"status\": \"not_converged\"") != std::string::npos);
}

TEST_CASE("a load step that cannot balance because a crack freed a piece names the piece and splits its residual",
          "[cli][fracture][load_path]") {
  // The right end's y-point becomes a small downward traction on the top face (100 Pa, 0.1 N
  // in all: the intact bar carries it in bending at under 1% of f_t). Held at first, so no
  // warning; once the bar has parted, the piece under the right grip is held along x only and
  // the traction drags it down: the balance cannot converge, and the run says which piece.
  ScratchDir d;
  const Outcome o = run_bar(d, "--set 'stages.0.boundary.3={region: top, traction: [0.0, -100.0]}' "
                               "--set solver.max_iterations=20000").o;
  INFO(o.out << o.err);
  CHECK(o.exit_code == 1);
  CHECK(o.err.find("rigid motion") == std::string::npos);  // the intact bar is held
  CHECK(o.err.find("the balance did not converge in 20000 ADR iterations (residual ") != std::string::npos);
  CHECK(o.err.find("(residual 0.000000") == std::string::npos);  // the residual in e-notation, with its target
  CHECK(o.err.find(", target 1.0e-") != std::string::npos);
  // A force loads the cracking bar: the message says what to do when it is past the peak.
  CHECK(o.err.find("; or the stage's forces are more than the cracking body can carry: to follow its path past the "
                   "peak, move the loaded region by a displacement") != std::string::npos);
  // The residual split between the particles the break detached and the rest of the body
  // (measured 7.516e-5 on 364 detached particles and 1.130e-5 on the rest, of 7.600e-5):
  // the two shares are the residual's, split by dofs.
  const auto failed = o.err.find("the balance did not converge in 20000 ADR iterations (residual ");
  REQUIRE(failed != std::string::npos);
  double total = 0.0, loose = 0.0, rest = 0.0;
  unsigned long count = 0;
  REQUIRE(std::sscanf(o.err.c_str() + failed,
                      "the balance did not converge in 20000 ADR iterations (residual %lf, target %*s of it, %lf on the "
                      "%lu detached particles and %lf on the rest of the body",
                      &total, &loose, &count, &rest) == 4);
  CHECK(count > 0);
  CHECK(loose > 0.0);
  CHECK(rest > 0.0);
  CHECK(std::sqrt(loose * loose + rest * rest) == Approx(total).epsilon(2e-3));  // (printed to 4 digits)
  const auto at = o.out.find("perinom: note: in stage 'pull' the cracks have left a piece of ");
  REQUIRE(at != std::string::npos);
  const std::string note = o.out.substr(at, o.out.find('\n', at) - at);
  CHECK(note.find("(of 2 piece(s), ") != std::string::npos);
  CHECK(note.find("that its supports do not hold: it can move along (0, 1)") != std::string::npos);
  CHECK(o.out.find("perinom: note: in stage 'pull' the cracks have left a piece", at + 1) == std::string::npos);  // one
}

TEST_CASE("solver.check: newton solves the broken notched beam again at its final damage state",
          "[cli][fracture][load_path][newton]") {
  // The notched beam coarsened to 5 mm (350 particles) and pulled past its peak: bonds break
  // at the notch tip in 22 steps, the load peaks at step 60 and falls by 44% in the next
  // (since the supports' ties are broken alike, 2026-12-07; before, by 14% at step 39 of 40).
  // Newton solves the final loads on the broken body (one step: it is linear elastic) with
  // the assembled tangent of the refreshed rows.
  ScratchDir d;
  const Outcome o = perinom(d, "run '" PERINOM_SOURCE_DIR "/examples/notched_beam.yaml' --out out "
                               "--set discretization.dx=0.005 --set stages.0.steps=64 "
                               "--set stages.0.boundary.2.displacement.y=-3.84e-5 --set solver.check=newton");
  INFO(o.out << o.err);
  REQUIRE(o.exit_code == 0);
  const auto t = columns(slurp(d.path / "out" / "load_steps.csv"));
  const std::vector<double>& R = t.at("stages.0.boundary.2.Ry");
  const auto peak = std::size_t(std::min_element(R.begin(), R.end()) - R.begin());  // the load pushes down
  REQUIRE(peak + 1 < R.size());
  CHECK(R.back() > 0.9 * R[peak]);  // past the peak: less load carried at the end
  double broken = 0.0;
  for (const double b : t.at("broken_bonds")) broken += b;
  CHECK(broken >= 10.0);
  const std::string summary = slurp(d.path / "out" / "summary.json");
  CHECK(summary.find("\"at\": \"final damage state\"") != std::string::npos);
  CHECK(summary.find("\"newton_converged\": true") != std::string::npos);
  // ADR balances to 1e-6 of the load; the two answers agree to that (measured 3.5e-6, stress 1.5e-5).
  CHECK(json_number(summary, "displacement_relative_l2") < 1e-4);
  CHECK(json_number(summary, "stress_relative_l2") < 1e-4);
  CHECK(o.out.find("perinom: Newton check at the final damage state") != std::string::npos);
}

TEST_CASE("solver.check: newton solves the beam with softening bonds again at its final damage state",
          "[cli][fracture][load_path][newton]") {
  // The same coarse beam with G_f = 143.2 N/m, 60 um in 100 steps: the load peaks at step 84
  // and ends 9% lower with 75 bonds softening, none spent, so the check meets bonds on their
  // secant (below their committed opening) and on the softening branch. Newton from zero with
  // the softening bonds' tangent rows (CohesiveBonds::tangent_row): measured 5 iterations,
  // displacement within 2.2e-6 and stress within 1.0e-5 of ADR's (tolerance 1e-6).
  ScratchDir d;
  const Outcome o = perinom(d, "run '" PERINOM_SOURCE_DIR "/examples/notched_beam.yaml' --out out "
                               "--set discretization.dx=0.005 --set stages.0.steps=100 "
                               "--set stages.0.boundary.2.displacement.y=-6.0e-5 --set solver.check=newton "
                               "--set damage.fracture_energy=143.2");
  INFO(o.out << o.err);
  REQUIRE(o.exit_code == 0);
  const auto t = columns(slurp(d.path / "out" / "load_steps.csv"));
  const std::vector<double>& R = t.at("stages.0.boundary.2.Ry");
  const auto peak = std::size_t(std::min_element(R.begin(), R.end()) - R.begin());  // the load pushes down
  CHECK(peak + 5 < R.size());
  CHECK(R.back() > 0.95 * R[peak]);  // past the peak: at least 5% less carried at the end
  const std::string summary = slurp(d.path / "out" / "summary.json");
  CHECK(json_number(summary, "softening_bonds_spent") == 0.0);
  CHECK(summary.find("\"newton_converged\": true") != std::string::npos);
  CHECK(json_number(summary, "newton_iterations") <= 10.0);
  CHECK(json_number(summary, "displacement_relative_l2") < 1e-4);
  CHECK(json_number(summary, "stress_relative_l2") < 1e-4);
}

TEST_CASE("the Newton check holds the detached particles of a shattered bar where the path left them",
          "[cli][fracture][load_path][newton]") {
  // The brittle bar with grips ends parted, 364 particles detached: their rows are empty, but
  // their live bonds enter their neighbours' gradients, so Newton must hold them where ADR
  // left them (held at zero, the answers differed by 12.7%). The pieces carry nothing, so
  // the stresses are rounding noise: the check compares them over the largest stress along
  // the path (before, it reported "stress by 1.169e-01", rounding over rounding, for two
  // answers 1.7e-9 apart on that scale).
  ScratchDir d;
  const BarRun b = run_bar(d, "--set solver.check=newton");
  INFO(b.o.out << b.o.err);
  REQUIRE(b.o.exit_code == 0);
  const std::string summary = slurp(d.path / "out" / "summary.json");
  CHECK(json_number(summary, "detached_held") > 300.0);
  CHECK(summary.find("\"newton_converged\": true") != std::string::npos);
  CHECK(json_number(summary, "displacement_relative_l2") < 1e-6);  // measured 7.6e-10
  CHECK(summary.find("\"stress_relative_to\": \"the largest along the path") != std::string::npos);
  CHECK(json_number(summary, "stress_relative_l2") < 1e-6);  // measured 1.7e-9 (the example's bar)
  CHECK(b.o.out.find("stress over the largest along the path") != std::string::npos);
}

TEST_CASE("the damaged Newton check of a resumed run compares the stress over the whole path", "[cli][fracture][load_path][newton][checkpoint]") {
  // examples/brittle_bar.yaml parts before load step 150; resumed there, the steps left are all
  // rounding for stress. The checkpoint keeps the path's largest stress norms: without them the
  // check compared rounding over rounding (1.2e-1) and warned that the answers differ.
  ScratchDir d;
  const std::string scene = "'" PERINOM_SOURCE_DIR "/examples/brittle_bar.yaml' --set solver.check=newton "
                            "--set output.checkpoint_every=150";
  const Outcome first = perinom(d, "run " + scene + " --out first");
  INFO(first.out << first.err);
  REQUIRE(first.exit_code == 0);
  const Outcome again = perinom(d, "run " + scene + " --restart first --out again");
  INFO(again.out << again.err);
  REQUIRE(again.exit_code == 0);
  REQUIRE(again.out.find("resuming from") != std::string::npos);
  const std::string summary = slurp(d.path / "again" / "summary.json");
  CHECK(summary.find("\"stress_relative_to\": \"the largest along the path") != std::string::npos);
  CHECK(json_number(summary, "stress_relative_l2") < 1e-6);  // measured 1.7e-9, as uninterrupted
  CHECK(again.out.find("differ by") == std::string::npos);
}

TEST_CASE("smoke: the four-point beam with two flaws, coarse, cracks first at the lower flaw's tip and softens",
          "[cli][fracture][load_path]") {
  // examples/four_point_beam.yaml at dx = 6.25 mm (26 x 12 particles) in 200 load steps (the
  // load strips lowered to the coarser top row): the first bond to break is within two
  // spacings of the lower flaw's tip T1 = (80, 21) mm (measured: at (78.1, 21.9) and (84.4, 21.9), step 49),
  // not at a support or under a load; the load passes a peak and falls; every step balanced.
  ScratchDir d;
  const Outcome o = perinom(d, "run '" PERINOM_SOURCE_DIR "/examples/four_point_beam.yaml' --out out "
                               "--set discretization.dx=0.00625 --set 'stages.0.boundary.2.region.box.min=[0.056, 0.07]' "
                               "--set 'stages.0.boundary.3.region.box.min=[0.1015, 0.07]' --set stages.0.steps=200 "
                               "--set output.csv=true --set 'output.vtk_steps=[200]'");
  INFO(o.out << o.err);
  REQUIRE(o.exit_code == 0);
  const auto t = columns(slurp(d.path / "out" / "load_steps.csv"));
  std::vector<double> P;
  for (std::size_t k = 0; k < t.at("step").size(); ++k)
    P.push_back(-(t.at("stages.0.boundary.2.Ry")[k] + t.at("stages.0.boundary.3.Ry")[k]));
  REQUIRE(P.size() == 200);
  const auto peak = std::size_t(std::max_element(P.begin(), P.end()) - P.begin());
  CHECK(peak > 0);
  CHECK(peak + 1 < P.size());
  CHECK(P.back() < 0.9 * P[peak]);
  for (const double r : t.at("residual")) CHECK(r <= 1e-6);
  const auto cloud = columns(slurp(d.path / "out" / "four_point_beam_000000.csv"));
  const std::vector<double>&x = cloud.at("x"), &y = cloud.at("y"), &event = cloud.at("break_event");
  double first = 0.0;  // the run's first event (the precracks are none)
  for (const double e : event)
    if (e > 0.0 && (first == 0.0 || e < first)) first = e;
  REQUIRE(first == 1.0);
  for (std::size_t i = 0; i < event.size(); ++i)
    if (event[i] == first) CHECK(std::hypot(x[i] - 0.080, y[i] - 0.021) < 2.0 * 0.00625);
}

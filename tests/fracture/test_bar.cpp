// A bar in uniaxial tension (examples/bar_tension.yaml), loaded slowly, breaking by the stress criterion (issue 17): the
// peak reaction is f_t times the cross-section within 1%, and the bar then carries nothing.
// The grips are no-fail zones (damage.no_fail): the classical formulation's stress is not
// uniform within two horizons of a held end (up to 3.7% above the interior's here), so
// without them the bar breaks at the grip, at a lower load.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "perinom/scene/problem.hpp"
#include "perinom/scene/registry.hpp"
#include "perinom/scene/scene.hpp"

using namespace perinom;

namespace {

// examples/bar_tension.yaml: 10 x 1 mm, 50 x 5 particles, plane stress steel, f_t = 100 MPa;
// the right end pulled at 0.05 m/s ramped over 20 us, so that it fails near 100 us (about 50
// wave transits: quasi-static); grips of three horizons at each end.
Scene bar_scene(bool grips) {
  std::vector<std::string> sets = {"output.vtk_every=0"};
  if (!grips) sets.push_back("damage.no_fail=[]");
  return read_scene(std::string(PERINOM_SOURCE_DIR) + "/examples/bar_tension.yaml", sets);
}

struct BarRun {
  SolveReport report;
  std::vector<double> R;  // the right grip's reaction (N), per history row
  std::size_t first_break = 0;  // the first row with broken bonds
  double end_time = 0.0, right_u = 0.0;
};

BarRun run_bar(bool grips) {
  Problem p = build_problem(bar_scene(grips));
  std::vector<double> u(p.physics().dofs(), 0.0);
  BarRun b;
  b.report = solve_problem(p, u);
  const History& h = b.report.history;
  const std::size_t cols = h.columns.size();
  const std::size_t c = std::find(h.columns.begin(), h.columns.end(), "boundary.2.Rx") - h.columns.begin();
  REQUIRE(c < cols);
  for (std::size_t r = 0; r < h.rows(); ++r) b.R.push_back(h.values[r * cols + c]);
  b.first_break = h.rows();
  for (std::size_t r = h.rows(); r-- > 0;)
    if (h.values[r * cols + cols - 2] == 0.0) {  // broken_bonds
      b.first_break = r + 1;
      break;
    }
  b.end_time = b.report.end_time;
  for (std::size_t i = 0; i < p.cloud.size(); ++i)
    if (p.cloud.x[i * 2] > 0.0098) b.right_u = u[i * 2];
  return b;
}

}  // namespace

TEST_CASE("a bar pulled slowly breaks at f_t times its cross-section and then carries nothing", "[fracture][bar]") {
  const BarRun b = run_bar(true);
  INFO(b.report.failure);
  REQUIRE(b.report.converged);
  const double ftA = 1.0e8 * 1.0e-3;  // f_t times 1 mm x the unit thickness
  // The load it fails at: the largest reaction up to the row of the first break (after it the
  // unbreakable grips ring with the energy they held).
  const std::size_t first = b.first_break;
  REQUIRE(first < b.R.size());
  CHECK(*std::max_element(b.R.begin(), b.R.begin() + first + 1) == Approx(ftA).epsilon(0.01));
  // Broken through: over the last fifth of the run the grip's reaction averages to nothing
  // (the freed halves ring about zero).
  const std::size_t tail = b.R.size() / 5;
  const double mean = std::accumulate(b.R.end() - tail, b.R.end(), 0.0) / tail;
  CHECK(std::abs(mean) < 0.02 * ftA);
  CHECK(b.report.changes.broken > 0);
  // The ramped velocity: the right end has moved v (t - T/2).
  CHECK(b.right_u == Approx(0.05 * (b.end_time - 1.0e-5)).epsilon(1e-9));
  // Energy: kinetic + strain + released - work, against the work (1.2% measured: the
  // breaking steps' accounting; docs/verification/bar.md).
  const History& h = b.report.history;
  const double* last = h.values.data() + h.values.size() - h.columns.size();
  CHECK(std::abs(last[5]) < 0.02 * last[4]);
}

TEST_CASE("without no-fail grips the bar breaks at a grip, below f_t times its cross-section", "[fracture][bar]") {
  // The stress next to a held end is up to 3.7% above the interior's: the first bonds break
  // there. This is the case the no-fail zones exist for.
  const BarRun b = run_bar(false);
  REQUIRE(b.report.converged);
  REQUIRE(b.first_break < b.R.size());
  const double peak = *std::max_element(b.R.begin(), b.R.begin() + b.first_break + 1);
  CHECK(peak < 0.99 * 1.0e8 * 1.0e-3);
  CHECK(peak > 0.9 * 1.0e8 * 1.0e-3);
}

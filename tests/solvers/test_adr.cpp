#include <catch2/catch.hpp>

#include "../support/clouds.hpp"
#include "../support/direct_solve.hpp"
#include "../support/pulled_bar.hpp"
#include "perinom/core/error.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/adr.hpp"

using namespace perinom;

namespace {

// The pulled bar (tests/support/pulled_bar.hpp) with a tight ADR tolerance and a tip probe.
const std::string bar = test::pulled_bar + R"(solver: {type: adr, tolerance: 1.0e-10, displacement_tolerance: 1.0e-12}
probes:
  - {name: tip, point: [0.06, 0.006], field: displacement, component: x}
)";

}  // namespace

TEST_CASE("ADR converges on a small bar to the direct solution and near the analytic one", "[solvers]") {
  Problem p = build_problem(parse_scene(bar, "bar"));
  std::vector<double> u;
  AdrOptions opt;
  opt.tolerance = 1e-10;
  opt.displacement_tolerance = 1e-12;
  const SolveReport rep = solve_adr(p.as<CorrespondenceModel>(), p.loading, opt, u);
  REQUIRE(rep.converged);
  const auto ref = test::direct_solve(p.as<CorrespondenceModel>(), p.loading);
  double err = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) err = std::max(err, std::abs(u[k] - ref[k]));
  CHECK(err <= 1e-7 * test::max_abs(ref));
  // Analytic tip displacement, measured across the loaded and the constrained layer centres.
  const std::size_t tip = p.probes[0].particles[0];
  const double L = 0.06 - 0.002, analytic = 1.0e6 * L / 30.0e6;
  const double rel = std::abs(u[tip * 2] - analytic) / analytic;
  WARN("bar tip: ADR " << u[tip * 2] << " m, analytic " << analytic << " m, relative difference "
                       << rel << " (classical surface effect), " << rep.iterations << " iterations");
  CHECK(rel < 0.05);
}

TEST_CASE("ADR stops cleanly on NaN, says why and keeps a finite state", "[solvers]") {
  Problem p = build_problem(parse_scene(bar, "bar"));
  p.loading.force[10] = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> u;
  const SolveReport rep = solve_adr(p.as<CorrespondenceModel>(), p.loading, AdrOptions{}, u);
  CHECK_FALSE(rep.converged);
  CHECK_THAT(rep.failure, Catch::Contains("NaN"));
  for (double x : u) REQUIRE(std::isfinite(x));
}

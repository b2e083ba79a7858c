#include <catch2/catch.hpp>

#include "../support/clouds.hpp"
#include "../support/direct_solve.hpp"
#include "perinom/core/error.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/adr.hpp"

using namespace perinom;

namespace {

// A plane-stress bar 60 mm x 12 mm, left end on rollers (u_x = 0, one particle also
// u_y = 0), pulled by a traction of 1 MPa on the right end. Analytic: u_x(L) = t L / E.
const char* bar = R"(
name: bar
dimension: 2
geometry: {box: {min: [0, 0], max: [0.06, 0.012]}, thickness: 0.01}
discretization: {dx: 0.002, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000, plane: stress}
boundary:
  - {region: left, fix: [x]}
  - {region: {box: {min: [0, 0], max: [0.002, 0.002]}}, fix: [y]}
  - {region: right, traction: [1.0e6, 0]}
solver: {type: adr, tolerance: 1.0e-10, displacement_tolerance: 1.0e-12}
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
  const SolveReport rep = solve_adr(*p.model, p.loading, opt, u);
  REQUIRE(rep.converged);
  const auto ref = test::direct_solve(*p.model, p.loading);
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
  const SolveReport rep = solve_adr(*p.model, p.loading, AdrOptions{}, u);
  CHECK_FALSE(rep.converged);
  CHECK_THAT(rep.failure, Catch::Contains("NaN"));
  for (double x : u) REQUIRE(std::isfinite(x));
}

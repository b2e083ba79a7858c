#include <catch2/catch.hpp>

#include "perinom/scene/problem.hpp"
#include "perinom/solvers/adr.hpp"

using namespace perinom;

TEST_CASE("the demo plate's top-centre displacement is within 5% of plane-strain FEM",
          "[verification]") {
  const Scene scene = read_scene(PERINOM_SOURCE_DIR "/examples/uniaxial_compression.yaml");
  Problem p = build_problem(scene);
  AdrOptions opt;
  opt.tolerance = scene.solver.tolerance;
  opt.displacement_tolerance = scene.solver.displacement_tolerance;
  std::vector<double> u;
  REQUIRE(solve_adr(*p.model, p.loading, opt, u).converged);
  const double uy = u[p.probes.at(0).particles.at(0) * 2 + 1], fem = -0.4466e-3;
  WARN("top_center_uy = " << uy << " m, FEM " << fem << " m, error " << (uy - fem) / -fem * 100 << "%");
  CHECK(std::abs(uy - fem) <= 0.05 * std::abs(fem));
  CHECK(uy < 0.0);
}

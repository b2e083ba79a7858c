// The NaN/Inf guard of the solvers: a solve that blows up stops at the first state that
// fails the guard, returns the state before it (the last that passed, with its own step and
// time), and keeps no history row past it, so nothing non-finite can be written.
#include <catch2/catch.hpp>

#include <cmath>

#include "perinom/core/error.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/scene.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/newton.hpp"
#include "perinom/solvers/verlet.hpp"

using namespace perinom;

namespace {

const char* plate = R"(
name: plate
dimension: 2
geometry: {box: {min: [0, 0], max: [0.012, 0.008]}}
discretization: {dx: 0.001, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0}
boundary:
  - {region: bottom, fix: [x, y]}
  - {region: top, pressure: 1.0e6}
)";

void require_finite(const std::vector<double>& values) {
  for (const double x : values) REQUIRE(std::isfinite(x));
}

}  // namespace

TEST_CASE("Verlet past its stable step stops at the guard and returns the step before", "[solvers]") {
  Problem p = build_problem(parse_scene(plate, "plate.yaml"));
  VerletOptions opt;
  opt.dt = 3.0 * stable_time_step(p.physics());
  opt.steps = 100000;
  opt.history_every = 1;
  opt.energy_check = false;  // the energy balance would stop it first; this is the NaN guard's test
  std::vector<double> u, v;
  std::int64_t observed = -1;
  Observer every{1, [&](std::int64_t step, double, const std::vector<double>& state) {
                   require_finite(state);
                   observed = step;
                 }};
  const SolveReport rep = solve_verlet(p.physics(), p.loading, opt, u, v, nullptr, every);
  INFO(rep.failure);
  CHECK(rep.diverged);
  CHECK_FALSE(rep.converged);
  CHECK(rep.failure.find("NaN or Inf") != std::string::npos);
  REQUIRE(rep.diverged_at > 10);
  CHECK(rep.iterations == rep.diverged_at - 1);
  CHECK(rep.end_time == Approx(rep.iterations * opt.dt).epsilon(1e-12));
  CHECK(observed == rep.iterations);  // every step that passed was observed, none after
  require_finite(u);
  require_finite(v);
  require_finite(rep.history.values);
  REQUIRE(rep.history.rows() == static_cast<std::size_t>(rep.iterations) + 1);  // steps 0 .. last good
  CHECK(rep.history.at(rep.history.rows() - 1, 0) == rep.iterations);
}

TEST_CASE("Verlet stopped by its energy balance returns the last state whose balance was checked", "[solvers]") {
  // The step before the failure was never checked (the balance is taken at history rows):
  // a run stopped at step 20 wrote "the last good state, step 19" with displacements of 1e30 m.
  Problem p = build_problem(parse_scene(plate, "plate.yaml"));
  VerletOptions opt;
  opt.dt = 1.2 * stable_time_step(p.physics());
  opt.steps = 100000;
  opt.history_every = 5;
  std::vector<double> u, v;
  std::vector<std::vector<double>> observed;
  Observer every{1, [&](std::int64_t, double, const std::vector<double>& state) { observed.push_back(state); }};
  const SolveReport rep = solve_verlet(p.physics(), p.loading, opt, u, v, nullptr, every);
  INFO(rep.failure);
  REQUIRE(rep.diverged);
  CHECK(rep.failure.find("energy balance failed at step " + std::to_string(rep.diverged_at)) != std::string::npos);
  CHECK(rep.failure.find("the last good state is step " + std::to_string(rep.iterations) +
                         ", the last whose energy balance was checked") != std::string::npos);
  REQUIRE(rep.diverged_at % 5 == 0);
  REQUIRE(rep.diverged_at > 10);
  CHECK(rep.iterations == rep.diverged_at - 5);
  CHECK(rep.end_time == Approx(rep.iterations * opt.dt).epsilon(1e-12));
  REQUIRE(observed.size() > static_cast<std::size_t>(rep.iterations));
  CHECK(u == observed[rep.iterations - 1]);  // observed[k] is step k + 1
  // The failing row is kept as the evidence: its balance is the one the guard refused.
  const std::size_t last = rep.history.rows() - 1;
  CHECK(rep.history.at(last, 0) == rep.diverged_at);
  const double e = rep.history.at(last, 2) + rep.history.at(last, 3), w = rep.history.at(last, 4);
  CHECK(std::abs(rep.history.at(last, 5)) > opt.energy_tolerance * std::max(e, std::abs(w)));
  require_finite(rep.history.values);
}

TEST_CASE("an observer that refuses a state is a failed guard: the state before is returned", "[solvers]") {
  Problem p = build_problem(parse_scene(plate, "plate.yaml"));
  std::vector<double> at_5;
  Observer refuse{1, [&](std::int64_t it, double, const std::vector<double>& state) {
                    if (it == 5) at_5 = state;
                    if (it == 6) throw SolveError("the snapshot's field 'stress' is NaN or Inf at particle 0");
                  }};
  SECTION("ADR") {
    AdrOptions opt;
    opt.history_every = 1;
    std::vector<double> u;
    const SolveReport rep = solve_adr(p.physics(), p.loading, opt, u, nullptr, refuse);
    CHECK(rep.diverged);
    CHECK(rep.diverged_at == 6);
    CHECK(rep.iterations == 5);
    CHECK(u == at_5);
    CHECK(rep.history.rows() == 5);
  }
  SECTION("Verlet") {
    VerletOptions opt;
    opt.history_every = 1;
    std::vector<double> u, v;
    const SolveReport rep = solve_verlet(p.physics(), p.loading, opt, u, v, nullptr, refuse);
    CHECK(rep.diverged);
    CHECK(rep.diverged_at == 6);
    CHECK(rep.iterations == 5);
    CHECK(u == at_5);
    CHECK(rep.history.rows() == 6);  // steps 0 to 5
  }
}

TEST_CASE("Newton on a non-finite residual keeps no -nan row and returns the last good state", "[solvers]") {
  Problem p = build_problem(parse_scene(plate, "plate.yaml"));
  NewtonOptions opt;
  opt.load_steps = 2;
  std::vector<double> u;
  // A good first load step, then a load that is NaN from the second step on.
  opt.after_step = [&](int step, const std::vector<double>&, long, double) {
    if (step == 1) p.loading.force[p.loading.force.size() / 2] = NAN;
  };
  // after_step is called by the load-path solvers; here the plain solve reads it too.
  const SolveReport first = solve_newton(p.physics(), p.loading, opt, u);
  INFO(first.failure);
  CHECK(first.diverged);
  CHECK(first.diverged_at == 2);
  require_finite(u);
  require_finite(first.history.values);
  CHECK(first.history.rows() == 1);
}

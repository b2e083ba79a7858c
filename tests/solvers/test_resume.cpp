// Resuming a solve from the state its checkpoint hook handed out part-way: ADR, Verlet and
// the load path (LBC, plain ADR) end exactly where the uninterrupted solve ends, bit for
// bit, and the state is what they continue from (a perturbed one ends elsewhere).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "../support/cli.hpp"
#include "../support/pulled_bar.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/load_path.hpp"
#include "perinom/solvers/verlet.hpp"

using namespace perinom;

namespace {

// The pulled bar of tests/support/pulled_bar.hpp.
const std::string& bar = perinom::test::pulled_bar;

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/// The states a hook is handed, kept.
template <class State>
Checkpoints<State> keep_all(std::vector<State>& states, std::int64_t every) {
  return {every, [&states](const State& s) { states.push_back(s); }};
}

/// The history without LBC's wall-time column (the last of the fixed ten).
std::vector<double> without_seconds(const History& h) {
  std::vector<double> out;
  for (std::size_t k = 0; k < h.values.size(); ++k)
    if (k % h.columns.size() != 9) out.push_back(h.values[k]);
  return out;
}

}  // namespace

TEST_CASE("ADR resumed from a state taken part-way ends bit for bit as the uninterrupted solve", "[solvers][checkpoint]") {
  Problem p = build_problem(parse_scene(bar, "bar"));
  AdrOptions opt;
  opt.tolerance = 1e-8, opt.load_steps = 2, opt.history_every = 7;
  std::vector<double> u;
  const SolveReport whole = solve_adr(p.as<CorrespondenceModel>(), p.loading, opt, u);
  REQUIRE(whole.converged);
  std::vector<AdrState> states;
  std::vector<double> u_ck;
  const SolveReport checkpointed = solve_adr(p.as<CorrespondenceModel>(), p.loading, opt, u_ck, nullptr, {}, keep_all(states, 150));
  CHECK(same_bits(u_ck, u));  // handing out the state changes nothing
  REQUIRE(states.size() >= 4);
  // One state in the first load step, one in the second.
  for (const AdrState* s : {&states[1], &states[states.size() - 2]}) {
    INFO("resumed at iteration " << s->iterations << ", load step " << s->load_step);
    std::vector<double> u_resumed;
    const SolveReport resumed = solve_adr(p.as<CorrespondenceModel>(), p.loading, opt, u_resumed, nullptr, {}, {}, s);
    CHECK(resumed.converged);
    CHECK(same_bits(u_resumed, u));
    CHECK(resumed.iterations == whole.iterations);
    CHECK(same_bits(resumed.history.values, whole.history.values));
    CHECK(std::memcmp(&resumed.residual, &whole.residual, sizeof(double)) == 0);
  }
  CHECK(states[1].load_step == 1);
  CHECK(states[states.size() - 2].load_step == 2);
  // The state is what it continues from: its largest velocity changed by a millionth ends
  // elsewhere (the same equilibrium, to the tolerance, but not the same bits).
  AdrState nudged = states[1];
  *std::max_element(nudged.v.begin(), nudged.v.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }) *=
      1.0 + 1e-6;
  std::vector<double> u_nudged;
  REQUIRE(solve_adr(p.as<CorrespondenceModel>(), p.loading, opt, u_nudged, nullptr, {}, {}, &nudged).converged);
  CHECK_FALSE(same_bits(u_nudged, u));
}

TEST_CASE("Verlet resumed from a state taken part-way ends bit for bit as the uninterrupted run", "[solvers][checkpoint]") {
  // Pulled by a traction, or by its right face moved (a Galerkin support whose multipliers
  // do the external work).
  const std::string right = GENERATE(std::string("traction: [1.0e6, 0]"), std::string("displacement: {x: 1.0e-5}, at: face"));
  INFO("right end: " << right);
  Problem p = build_problem(parse_scene(cli_test::with(bar, "traction: [1.0e6, 0]", right), "bar"));
  REQUIRE(p.loading.galerkin() == (right.find("face") != std::string::npos));
  VerletOptions opt;
  opt.steps = 300, opt.history_every = 7, opt.ramp_time = 100 * 0.8 * stable_time_step(p.as<CorrespondenceModel>());
  std::vector<double> u, v;
  const SolveReport whole = solve_verlet(p.as<CorrespondenceModel>(), p.loading, opt, u, v);
  REQUIRE(whole.converged);
  std::vector<VerletState> states;
  std::vector<double> u_ck, v_ck;
  solve_verlet(p.as<CorrespondenceModel>(), p.loading, opt, u_ck, v_ck, nullptr, {}, keep_all(states, 90));
  CHECK(same_bits(u_ck, u));
  REQUIRE(states.size() == 3);
  CHECK(states[0].multipliers.size() == (p.loading.galerkin() ? p.loading.fixed.size() : 0));
  for (const VerletState& s : states) {  // during the ramp (90) and after it (180, 270)
    INFO("resumed at step " << s.step);
    std::vector<double> u_resumed, v_resumed;
    const SolveReport resumed = solve_verlet(p.as<CorrespondenceModel>(), p.loading, opt, u_resumed, v_resumed, nullptr, {}, {}, &s);
    CHECK(resumed.converged);
    CHECK(same_bits(u_resumed, u));
    CHECK(same_bits(v_resumed, v));
    CHECK(same_bits(resumed.history.values, whole.history.values));
    CHECK(std::memcmp(&resumed.end_time, &whole.end_time, sizeof(double)) == 0);
  }
  VerletState nudged = states[0];
  nudged.work = std::nextafter(nudged.work, 1.0);  // only the history's work column sees it
  std::vector<double> u_nudged, v_nudged;
  const SolveReport off = solve_verlet(p.as<CorrespondenceModel>(), p.loading, opt, u_nudged, v_nudged, nullptr, {}, {}, &nudged);
  CHECK(same_bits(u_nudged, u));
  CHECK_FALSE(same_bits(off.history.values, whole.history.values));
}

TEST_CASE("a load path resumed after a committed step ends bit for bit as the uninterrupted one", "[solvers][checkpoint][load_path]") {
  // The biaxial example coarsened, three steps a stage: plastic from the first step.
  const std::vector<std::string> set = {"stages.0.steps=3", "stages.1.steps=3", "discretization.dx=0.005"};
  const auto build = [&] { return build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/biaxial_compression.yaml", set)); };
  LoadPathOptions opt;
  opt.adr.tolerance = opt.adr.displacement_tolerance = 1e-9;
  opt.scheme = GENERATE(LoadPathScheme::lbc, LoadPathScheme::every_iteration);
  INFO((opt.scheme == LoadPathScheme::lbc ? "LBC" : "plain ADR, the return map committed every iteration"));
  Problem whole_p = build();
  std::vector<double> u;
  const SolveReport whole = solve_load_path(whole_p.as<CorrespondenceModel>(), whole_p.stages, opt, u);
  REQUIRE(whole.converged);
  const auto& plastic = whole_p.as<CorrespondenceModel>().plastic()->committed();
  REQUIRE(plastic[0].law.xi > 0.0);
  std::vector<LoadPathState> states;
  {
    Problem p = build();
    std::vector<double> u_ck;
    solve_load_path(p.as<CorrespondenceModel>(), p.stages, opt, u_ck, nullptr, {}, keep_all(states, 1));
    CHECK(same_bits(u_ck, u));
  }
  REQUIRE(states.size() == 6);
  // After step 3 (the next stage begins), 4 (the predictor's base is the stage's start) and 5.
  for (const LoadPathState* s : {&states[2], &states[3], &states[4]}) {
    INFO("resumed after load step " << s->step << " of stage " << s->stage + 1);
    Problem p = build();
    std::vector<double> u_resumed;
    const SolveReport resumed = solve_load_path(p.as<CorrespondenceModel>(), p.stages, opt, u_resumed, nullptr, {}, {}, s);
    CHECK(resumed.converged);
    CHECK(same_bits(u_resumed, u));
    CHECK(resumed.iterations == whole.iterations);
    CHECK(same_bits(without_seconds(resumed.history), without_seconds(whole.history)));
    const auto& resumed_plastic = p.as<CorrespondenceModel>().plastic()->committed();
    REQUIRE(resumed_plastic.size() == plastic.size());
    CHECK(std::memcmp(resumed_plastic.data(), plastic.data(), plastic.size() * sizeof(plastic[0])) == 0);
    CHECK(p.as<CorrespondenceModel>().plastic()->flags() == whole_p.as<CorrespondenceModel>().plastic()->flags());
  }
  // The plastic history is part of the state: without it the path ends elsewhere.
  LoadPathState virgin = states[3];
  std::fill(virgin.plastic.begin(), virgin.plastic.end(), 0.0);
  Problem p = build();
  std::vector<double> u_virgin;
  solve_load_path(p.as<CorrespondenceModel>(), p.stages, opt, u_virgin, nullptr, {}, {}, &virgin);
  CHECK_FALSE(same_bits(u_virgin, u));
  // A step table of another width (a checkpoint of a version with other columns) is refused,
  // even where its length happens to divide by this run's width.
  const std::size_t width = whole.history.columns.size();
  REQUIRE(states[3].history.size() == 4 * width);
  for (const std::size_t values : {4 * (width - 1), 3 * width}) {
    LoadPathState other = states[3];
    other.history.resize(values);
    Problem q = build();
    std::vector<double> u_other;
    CHECK_THROWS_WITH(solve_load_path(q.as<CorrespondenceModel>(), q.stages, opt, u_other, nullptr, {}, {}, &other),
                      Catch::Contains("the resumed step table holds") && Catch::Contains("for 4 load steps"));
  }
}

TEST_CASE("a finite-rotation load path resumed after a committed step ends bit for bit as the uninterrupted one", "[solvers][checkpoint][load_path]") {
  // The wrapper law's checkpoint: the Drucker-Prager states and F (FiniteRotationLaw).
  const std::vector<std::string> set = {"stages.0.steps=2", "stages.1.steps=2", "discretization.dx=0.005",
                                        "model.kinematics=finite_rotation"};
  const auto build = [&] { return build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/biaxial_compression.yaml", set)); };
  LoadPathOptions opt;
  opt.adr.tolerance = opt.adr.displacement_tolerance = 1e-9;
  Problem whole_p = build();
  std::vector<double> u;
  const SolveReport whole = solve_load_path(whole_p.as<CorrespondenceModel>(), whole_p.stages, opt, u);
  REQUIRE(whole.converged);
  std::vector<LoadPathState> states;
  {
    Problem p = build();
    std::vector<double> u_ck;
    solve_load_path(p.as<CorrespondenceModel>(), p.stages, opt, u_ck, nullptr, {}, keep_all(states, 1));
  }
  REQUIRE(states.size() == 4);
  REQUIRE(whole_p.as<CorrespondenceModel>().history()->values_per_particle() == 37);
  Problem p = build();
  std::vector<double> u_resumed;
  const SolveReport resumed = solve_load_path(p.as<CorrespondenceModel>(), p.stages, opt, u_resumed, nullptr, {}, {}, &states[2]);
  CHECK(resumed.converged);
  CHECK(same_bits(u_resumed, u));
  CHECK(same_bits(without_seconds(resumed.history), without_seconds(whole.history)));
  // F is part of the state: reset to I, the path ends elsewhere.
  LoadPathState lost = states[2];
  for (std::size_t i = 0; i < lost.flags.size(); ++i)
    for (int k = 0; k < 9; ++k) lost.plastic[i * 37 + 28 + k] = k % 4 == 0 ? 1.0 : 0.0;
  Problem q = build();
  std::vector<double> u_lost;
  solve_load_path(q.as<CorrespondenceModel>(), q.stages, opt, u_lost, nullptr, {}, {}, &lost);
  CHECK_FALSE(same_bits(u_lost, u));
}

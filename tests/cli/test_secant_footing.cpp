// Prandtl's strip footing (verification/footing/footing.yaml) at 4 particles across its
// half-width, pressed 15 cm in 60 steps. With the elastic stabilization the reaction keeps
// rising (1.46 -> 1.56 times Prandtl from 10 to 15 cm: S resists the mechanism's flow and
// never yields); with model.stabilization_scale: secant it levels off (1.193 -> 1.197), and
// LBC and Newton agree on it (the factors change only as a load step begins, so the tangent
// stays the force's). Measured at three spacings in docs/verification/README.md.
#include "../support/cli.hpp"

#include <cmath>

using namespace cli_test;

namespace {

const std::string footing = "'" PERINOM_SOURCE_DIR "/verification/footing/footing.yaml'";
const double prandtl = (2.0 + M_PI) * 2.0 * 1.0e5 / std::sqrt(3.0);  // (2 + pi) k b, N per m

/// The footing's reaction over Prandtl's, step by step.
std::vector<double> reactions(const fs::path& csv) {
  std::istringstream in(slurp(csv));
  std::string line;
  std::getline(in, line);  // the header: the footing's Ry is the last column
  std::vector<double> r;
  while (std::getline(in, line)) r.push_back(-std::stod(line.substr(line.rfind(',') + 1)) / prandtl);
  return r;
}

/// Runs the footing into dir/a and dir/b with the common and each run's --set options,
/// requires both to succeed, and returns their reactions (the second run's output in `out`).
std::pair<std::vector<double>, std::vector<double>> two_runs(const ScratchDir& dir, const std::string& common,
                                                             const std::string& a, const std::string& b,
                                                             std::string* out = nullptr) {
  const Outcome first = perinom(dir, "run " + footing + " --out a" + common + a);
  const Outcome second = perinom(dir, "run " + footing + " --out b" + common + b);
  INFO(first.out << first.err << second.out << second.err);
  REQUIRE(first.exit_code == 0);
  REQUIRE(second.exit_code == 0);
  if (out) *out = first.out + second.out;
  return {reactions(dir.path / "a" / "load_steps.csv"), reactions(dir.path / "b" / "load_steps.csv")};
}

}  // namespace

TEST_CASE("a secant stabilization lets Prandtl's footing level off where the elastic one keeps rising", "[cli][plastic]") {
  ScratchDir dir;
  std::string out;
  const auto [e, s] = two_runs(dir, " --set discretization.dx=0.25 --set boundary[3].displacement.y=-0.15 --set solver.load_steps=60",
                               "", " --set model.stabilization_scale=secant", &out);
  REQUIRE(e.size() == 60);
  REQUIRE(s.size() == 60);
  INFO("elastic " << e[39] << " -> " << e[59] << ", secant " << s[39] << " -> " << s[59]);
  CHECK(e[59] - e[39] > 0.05);  // measured 0.094
  CHECK(s[59] - s[39] < 0.01);  // measured 0.004
  CHECK(s[59] < 0.8 * e[59]);   // 1.197 against 1.555
  CHECK(s[59] > 1.0);           // above the limit load, as every run at this spacing
  // The elastic run's note points to secant; the secant run's says what it does.
  CHECK(out.find("model.stabilization_scale: secant (S follows") != std::string::npos);
  CHECK(out.find("perinom: note: material drucker_prager, model.stabilization_scale secant") != std::string::npos);
}

TEST_CASE("with a secant stabilization LBC and Newton agree on the footing", "[cli][plastic]") {
  ScratchDir dir;
  const auto [a, b] = two_runs(dir, " --set discretization.dx=0.25 --set model.stabilization_scale=secant", "",
                               " --set solver.type=newton");
  REQUIRE(a.size() == b.size());
  for (std::size_t k = 0; k < a.size(); ++k) CHECK(a[k] == Approx(b[k]).epsilon(1e-6));  // measured 8e-9 at the end
  // The factors move as a step begins, not at its commit: the final state keeps the force it
  // was balanced with, and the summary's equilibrium is the balance's (it was 4e-4 when the
  // last commit rescaled S under the reported reactions).
  for (const char* run : {"a", "b"}) {
    INFO(run);
    CHECK(json_number(slurp(dir.path / run / "summary.json"), "error") < 1e-6);
  }
}

TEST_CASE("model.stabilization_scale: secant on an elastic material is refused", "[cli]") {
  require_rejected(tiny_scene + "model: {stabilization_scale: secant}\n",
                   {"model.stabilization_scale: secant follows a drucker_prager material's plastic states"});
}

TEST_CASE("model.stabilization_scale: secant with a stored stabilization is refused", "[cli]") {
  const std::string plastic = with(tiny_scene, "type: linear_elastic", "type: drucker_prager\n  friction_angle: 0.0\n  cohesion: 1.0e6");
  require_rejected(plastic + "model: {stabilization_scale: secant, stabilization_storage: assembled}\n",
                   {"model.stabilization_scale: secant scales each family's block of S"});
}

TEST_CASE("model.stabilization_scale takes elastic or secant", "[cli]") {
  require_rejected(tiny_scene + "model: {stabilization_scale: plastic}\n", {"model.stabilization_scale: must be elastic or secant"});
}

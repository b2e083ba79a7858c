// The load path needs of a model only TangentModel and ModelHistory: a model that forwards
// every call to a plastic correspondence model, and is known to the load path by those two
// interfaces alone, follows the same path bit for bit, through the history calls it counts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>

#include "perinom/scene/problem.hpp"
#include "perinom/solvers/load_path.hpp"
#include "../support/pulled_bar.hpp"

using namespace perinom;

namespace {

/// Forwards to a model; counts the history calls the load path makes.
class Forwarding : public TangentModel, public ModelHistory {
 public:
  explicit Forwarding(TangentModel& m) : m_(m), h_(*m.history()) {}
  std::size_t particles() const override { return m_.particles(); }
  int dofs_per_particle() const override { return m_.dofs_per_particle(); }
  void internal_force(const double* u, double* f) override { m_.internal_force(u, f); }
  double energy(const double* u) override { return m_.energy(u); }
  std::vector<double> lumped_mass() const override { return m_.lumped_mass(); }
  std::vector<double> stiffness_row_sums() const override { return m_.stiffness_row_sums(); }
  std::vector<std::pair<std::string, std::size_t>> memory() const override { return m_.memory(); }
  void follow_loads(const Loading& loading, double s) override { m_.follow_loads(loading, s); }
  void visit_tangent_rows(const TangentRowVisitor& visit) const override { m_.visit_tangent_rows(visit); }
  void prepare_tangent(const double* u) override { m_.prepare_tangent(u); }
  ModelHistory* history() override { return this; }

  void set_history_mode(HistoryMode mode) override { ++modes, h_.set_history_mode(mode); }
  void commit(const double* u) override { ++commits, h_.commit(u); }
  void commit_trial() override { h_.commit_trial(); }
  std::size_t flag_violations(double tolerance) override { ++flag_rounds; return h_.flag_violations(tolerance); }
  std::vector<double> history_variable() const override { return h_.history_variable(); }
  std::size_t values_per_particle() const override { return h_.values_per_particle(); }
  HistoryState save_history() const override { return h_.save_history(); }
  void restore_history(const HistoryState& s) override { h_.restore_history(s); }
  void reset_history() override { h_.reset_history(); }

  int modes = 0, commits = 0, flag_rounds = 0;

 private:
  TangentModel& m_;
  ModelHistory& h_;
};

Problem biaxial(const std::string& solver) {
  return build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/biaxial_compression.yaml",
                                  {"stages.0.steps=2", "stages.1.steps=2", "solver.type=" + solver}));
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("the load path drives any model through TangentModel and ModelHistory", "[solvers][load_path]") {
  const std::string solver = GENERATE(std::string("lbc"), std::string("newton"));
  INFO("solver.type " << solver);
  LoadPathOptions opt;
  parse_load_path_scheme(solver, opt.scheme);
  Problem direct = biaxial(solver);
  REQUIRE(direct.physics().history() != nullptr);
  std::vector<double> u_direct;
  const SolveReport a = solve_load_path(direct.physics(), direct.stages, opt, u_direct);
  REQUIRE(a.converged);

  Problem p = biaxial(solver);
  Forwarding model(p.physics());
  std::vector<double> u;
  const SolveReport b = solve_load_path(model, p.stages, opt, u);
  REQUIRE(b.converged);
  CHECK(same_bits(u, u_direct));
  CHECK(b.iterations == a.iterations);
  CHECK(model.modes == 1);
  CHECK(model.commits == 4);  // one per load step
  if (solver == "lbc") CHECK(model.flag_rounds >= 4);
  const HistoryState h = model.save_history(), h_direct = direct.physics().history()->save_history();
  CHECK(same_bits(h.values, h_direct.values));
  CHECK(h.flags == h_direct.flags);
}

TEST_CASE("a model's history saved and restored is the same history", "[solvers][load_path]") {
  Problem p = biaxial("lbc");
  std::vector<double> u;
  LoadPathOptions opt;
  REQUIRE(solve_load_path(p.physics(), p.stages, opt, u).converged);
  ModelHistory& h = *p.physics().history();
  const HistoryState saved = h.save_history();
  REQUIRE(saved.values.size() == h.values_per_particle() * p.physics().particles());
  const std::vector<double> xi = h.history_variable();
  CHECK(*std::max_element(xi.begin(), xi.end()) > 0.0);
  h.reset_history();
  for (const double x : h.history_variable()) CHECK(x == 0.0);
  h.restore_history(saved);
  CHECK(same_bits(h.history_variable(), xi));
  CHECK_THROWS_AS(h.restore_history({std::vector<double>(3, 0.0), {}}), std::invalid_argument);
}

TEST_CASE("an elastic model has no history and its load path commits nothing", "[solvers][load_path]") {
  Problem p = build_problem(parse_scene(test::pulled_bar + "solver: {type: lbc, load_steps: 2}\n", "bar.yaml"));
  CHECK(p.physics().history() == nullptr);
  std::vector<double> u;
  const SolveReport rep = solve_load_path(p.physics(), p.stages, LoadPathOptions{}, u);
  CHECK(rep.converged);
}

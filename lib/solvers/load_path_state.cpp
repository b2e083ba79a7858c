#include "load_path_state.hpp"

#include <stdexcept>
#include <string>

namespace perinom::detail {

int restore(Model& model, std::vector<LoadStage>& stages, const LoadPathState& st,
            std::vector<double>& u, SolveReport& rep) {
  const bool fits = st.stage >= 0 && st.stage < int(stages.size()) && st.step >= 1 && st.step <= stages[st.stage].steps &&
                    st.stage_value0.size() == std::size_t(st.stage) + 1 && st.u.size() == u.size() &&
                    st.u_prev.size() == u.size() && (model.history() || st.plastic.empty());
  if (!fits) throw std::invalid_argument("solve_load_path: the resumed state does not fit the model and stages");
  // One row per load step done: a table of another width (a checkpoint written by a version
  // of perinom with other columns) would otherwise be read as rows cut at the wrong places.
  const std::size_t rows = std::size_t(steps_done(st, stages)), width = rep.history.columns.size();
  if (st.history.size() != rows * width)
    throw std::invalid_argument("solve_load_path: the resumed step table holds " + std::to_string(st.history.size()) +
                                " values for " + std::to_string(rows) + " load steps, not " + std::to_string(width) +
                                " a step (the columns this run writes; a checkpoint of another perinom version?)");
  u = st.u;
  rep.iterations = st.iterations;
  rep.residual = st.residual;
  rep.history.values = st.history;
  if (ModelHistory* h = model.history()) h->restore_history({st.plastic, st.flags});
  for (int j = 0; j <= st.stage; ++j) {
    Loading& loading = stages[j].loading;
    loading.begin_stage(j > 0 ? &stages[j - 1].loading : nullptr, u.data());
    if (st.stage_value0[j].size() != loading.fixed.size())
      throw std::invalid_argument("solve_load_path: a resumed stage start does not fit its constraints");
    loading.value0 = st.stage_value0[j];
  }
  return steps_done(st, stages);
}

LoadPathState state_after(const Model& model, const std::vector<LoadStage>& stages, int k, int step,
                          const std::vector<double>& u, const std::vector<double>& u_prev, const SolveReport& rep) {
  LoadPathState st;
  st.stage = k, st.step = step, st.iterations = rep.iterations, st.residual = rep.residual;
  st.residual_force = rep.residual_force, st.stiffness_force = rep.stiffness_force;
  st.at_rounding_floor = rep.at_rounding_floor;
  st.u = u, st.u_prev = u_prev;
  for (int j = 0; j <= k; ++j) st.stage_value0.push_back(stages[j].loading.value0);
  if (const ModelHistory* h = model.history()) {
    HistoryState saved = h->save_history();
    st.plastic = std::move(saved.values), st.flags = std::move(saved.flags);
  }
  st.history = rep.history.values;
  return st;
}

}  // namespace perinom::detail

namespace perinom {

int steps_done(const LoadPathState& state, const std::vector<LoadStage>& stages) {
  int done = state.step;
  for (int j = 0; j < state.stage && j < int(stages.size()); ++j) done += stages[j].steps;
  return done;
}

}  // namespace perinom

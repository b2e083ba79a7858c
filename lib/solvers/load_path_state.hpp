#pragma once
// The load path's checkpoint state (LoadPathState): taken after a committed step, and put
// back to resume from it. Private to solve_load_path.
#include <vector>

#include "perinom/solvers/load_path.hpp"

namespace perinom::detail {

/// Puts a resumed state back: u, the counters and rows, the plastic states, and where every
/// stage begun started (force0 follows from the stages before it, value0 is where the body
/// was). Returns the load steps done. Throws std::invalid_argument for a state that does
/// not fit the model, stages or history columns.
int restore(Model& model, std::vector<LoadStage>& stages, const LoadPathState& st,
            std::vector<double>& u, SolveReport& rep);

/// The state after step `step` (from 1) of stage k (from 0).
LoadPathState state_after(const Model& model, const std::vector<LoadStage>& stages, int k, int step,
                          const std::vector<double>& u, const std::vector<double>& u_prev, const SolveReport& rep);

}  // namespace perinom::detail

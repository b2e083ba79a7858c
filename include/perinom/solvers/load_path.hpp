#pragma once
/// @file Quasi-static load paths for plastic (and elastic) scenes: stages of load steps,
/// each solved by loading-balance-correction, by plain ADR with the plastic update in
/// every iteration, or by Newton with the consistent tangent (THEORY sec. 8).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "perinom/core/progress.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/models/model_history.hpp"
#include "perinom/models/tangent_model.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/model_changes.hpp"
#include "perinom/solvers/newton.hpp"

namespace perinom {

/// lbc: balance by ADR with trial stresses from the committed state, correction flags the
///      particles whose trial leaves the yield surface, commit when no new one is flagged;
/// every_iteration: ADR with the return map committed after every iteration (the explicit
///      scheme that yields falsely; for comparison);
/// newton: KINSOL (UMFPACK or KLU) on each load step with the consistent tangent, commit after it.
enum class LoadPathScheme { lbc, every_iteration, newton };
/// Parses "lbc", "adr", "newton"; false if unknown.
bool parse_load_path_scheme(const std::string& solver_type, LoadPathScheme& s);

struct LoadPathOptions {
  LoadPathScheme scheme = LoadPathScheme::lbc;
  AdrOptions adr;          ///< tolerances; max_iterations per balance (per load step for every_iteration)
  NewtonOptions newton;    ///< tolerances (load_steps and after_step are set per stage)
  double yield_tolerance = 1e-6;  ///< LBC: f > tol * m (A I1 + B) flags a particle
  int max_rounds = 1000;          ///< balance rounds per load step: LBC's corrections and bond breaking
  /// A failed step's report says whether the state it left is an unstable equilibrium (a
  /// stiffness that gives way there; lib/solvers/unstable_state.hpp): a sparse factorization
  /// of the whole model's tangent, up to 20,000 free dofs in 2-D and 4,000 in 3-D. Off for an
  /// MPI rank's part.
  bool diagnose_unstable_state = true;
};

/// What one load step took.
struct LoadStepRecord {
  int stage = 0, step = 0;            ///< from 1
  double load_factor = 0.0;           ///< within the stage
  std::int64_t iterations = 0;        ///< ADR iterations (all rounds) or Newton iterations
  int rounds = 0;                     ///< LBC balance-correction rounds (1: none flagged)
  std::size_t newly_flagged = 0;      ///< LBC: particles flagged in this step
  std::size_t yielding = 0;           ///< particles whose xi grew in this step
  std::size_t plastic = 0;            ///< particles with xi > 0
  std::size_t broken = 0;             ///< with changes: bonds broken in this step
  double residual = 0.0;              ///< relative residual at the end of the step
  double seconds = 0.0;
  /// For after_step: the report's history so far, this step's row the last (so an observer
  /// can write the table while the path goes on).
  const History* rows = nullptr;
};

/// Where a load path stands after a committed load step: with it the path continues bit
/// for bit (solve_load_path's `resume`). The balance itself starts from rest in every step,
/// so nothing of ADR is kept.
struct LoadPathState {
  int stage = 0;                ///< the stage of the last committed step (from 0)
  int step = 0;                 ///< that step within the stage (from 1)
  std::int64_t iterations = 0;  ///< ADR iterations over all steps
  double residual = 0.0;        ///< the step's relative residual
  /// The step's last balance: its residual force and stiffness force (N) and whether it met
  /// the rounding floor (SolveReport), for a path resumed with no step left to balance.
  double residual_force = 0.0, stiffness_force = 0.0;
  bool at_rounding_floor = false;
  /// dofs() values each: u now, and u at the step before (the predictor's base; u at the
  /// stage's start after its first step).
  std::vector<double> u, u_prev;
  /// Loading::value0 of every stage begun, in order (where each one started).
  std::vector<std::vector<double>> stage_value0;
  /// The model's committed history (ModelHistory::save_history: values_per_particle() reals
  /// a particle) and LBC's flags; both empty for a model without history.
  std::vector<double> plastic;
  std::vector<std::uint8_t> flags;
  std::vector<double> history;                ///< the history rows so far (History::values)
  std::vector<double> changes;                ///< with changes: ModelChanges::save(), else empty
  double carried = 0.0;                       ///< with changes: the largest reaction norm so far (N)
};

/// The load steps a state has done, counted over all stages (as output.vtk_steps counts).
int steps_done(const LoadPathState& state, const std::vector<LoadStage>& stages);

/// Runs the stages in order on any model (the Newton scheme: a TangentModel, else
/// std::invalid_argument); a model with history
/// (Model::history(), model_history.hpp) is evaluated by the scheme's mode and committed after
/// every load step, LBC flagging its particles; a model without history is solved elastic.
/// Runs the stages in order, each from where the previous ended (Loading::begin_stage).
/// after_step (if set) sees every committed step. report.history has one row per load step
/// (the LoadStepRecord fields); report.iterations counts all ADR or Newton iterations.
/// Stops at the first step that fails, with report.failure saying where.
/// `checkpoints` receives the whole state after the load steps it is due (counted over all
/// stages, after after_step); with `resume` (such a state) the path continues from it, and
/// ends with the u, plastic states, report and history the uninterrupted one would. The
/// Newton scheme takes neither (KINSOL's state is not kept): std::invalid_argument.
/// With `changes` (bonds that break; lbc and adr schemes only), each load step is a fixed
/// point: balance (and LBC's corrections), then at the balanced u the force, find(), and
/// when anything is due apply() and balance again, until a balance leaves nothing due, at
/// most max_rounds balances (then the step fails, saying so). Each balance's residual is
/// relative to at least the largest reaction norm the path has reached (a body broken apart
/// carries none: AdrRelaxation::set_load_floor). The history gains the column broken_bonds
/// (per step) and, for a model without history, external_work and dissipated_energy
/// (energy_ledger.hpp); checkpoints hold the changes (save) and resume restores them. With
/// changes that dissipate (softening bonds) ADR damps by the correction too
/// (AdrRelaxation::damp_by_correction).
SolveReport solve_load_path(Model& model, std::vector<LoadStage>& stages,
                            const LoadPathOptions& options, std::vector<double>& u,
                            Progress* progress = nullptr,
                            const std::function<void(const LoadStepRecord&, const std::vector<double>&)>&
                                after_step = {},
                            const Checkpoints<LoadPathState>& checkpoints = {}, const LoadPathState* resume = nullptr,
                            const ModelChanges* changes = nullptr);

}  // namespace perinom

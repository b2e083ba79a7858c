#pragma once
/// @file Adaptive dynamic relaxation (THEORY sec. 8; Kilic and Madenci 2010).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "perinom/core/progress.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/models/model.hpp"
#include "perinom/solvers/history.hpp"

namespace perinom {

struct AdrOptions {
  double tolerance = 1e-8;               ///< |R_free| / load norm
  double displacement_tolerance = 1e-8;  ///< |u^(n+1) - u^n| / |u^(n+1)| (seed 000 eq. 33)
  std::int64_t max_iterations = 200000;  ///< over all load steps
  int load_steps = 1;                    ///< loads ramped linearly over this many steps
  std::int64_t history_every = 10;       ///< a history row every this many iterations
};

struct SolveReport {
  bool converged = false;
  std::int64_t iterations = 0;
  double residual = 0.0;             ///< final relative residual
  double displacement_change = 0.0;  ///< final relative displacement increment
  /// Static solves: the final residual force |F| (N) and the size of the terms the internal
  /// force at the final u sums (rounding_force.hpp, N). at_rounding_floor: converged with |F|
  /// below their rounding while the relative residual was above the tolerance, because the
  /// loads and reactions it is measured against are rounding themselves (a stress-free
  /// rigid motion).
  double residual_force = 0.0, stiffness_force = 0.0;
  bool at_rounding_floor = false;
  double stable_time_step = 0.0;     ///< Verlet only (s)
  double end_time = 0.0;             ///< Verlet only: simulated time reached (s)
  std::string failure;               ///< why the solve stopped early (NaN or Inf), or empty
  /// A load path that converged on a body turning with its loads (Model::turns_with_body):
  /// why its end state is an unstable equilibrium ("an unstable equilibrium: its stiffness
  /// gives way ..."), or empty (stable, not examined, or another solver).
  std::string unstable_end;
  /// The NaN/Inf guard stopped the solve at iteration or step `diverged_at`; `iterations`
  /// and `end_time` then describe the last state that passed the guard (the one returned).
  bool diverged = false;
  std::int64_t diverged_at = -1;
  History history;
  /// Verlet with ModelChanges (breaking bonds): the wall time of the step loop, the part of it
  /// spent looking for changes (find), the part spent making them (apply, with the force and
  /// the released energy it updates, and the stable step), and the steps that made any.
  struct Changes {
    std::int64_t changing_steps = 0;
    double loop_seconds = 0.0, find_seconds = 0.0, change_seconds = 0.0;
    std::int64_t broken = 0;    ///< bonds broken during the run (set by whoever breaks them)
    std::int64_t detached = 0;  ///< particles detached so far, precracks included (likewise)
    std::int64_t step_reductions = 0;  ///< times the changes lowered the time step (Verlet)
    double final_dt = 0.0;             ///< the time step at the end (Verlet with changes)
    /// The instability criterion (set by whoever breaks bonds): the step it armed at (-1: not
    /// armed, or another criterion) and the s_hg_max it fixed then.
    std::int64_t armed_step = -1;
    double hourglass_threshold = 0.0;
    /// Softening bonds (damage.fracture_energy; set by whoever breaks bonds): how many carry
    /// nothing more (opened past eta_u; -1: no softening), and eta_u (m).
    std::int64_t spent = -1;
    double opening_limit = 0.0;
  };
  Changes changes;
};

/// What solve_adr carries from one iteration to the next, taken at the end of an iteration:
/// with it the solve continues bit for bit (solve_adr's `resume`).
struct AdrState {
  int load_step = 1;                 ///< the load step being balanced (from 1)
  std::int64_t iterations = 0;       ///< over all load steps
  double residual = 0.0;             ///< the relative residual at u
  double displacement_change = 0.0;  ///< of the last iteration
  double damping = 0.0;              ///< of the last iteration (its history row's)
  /// dofs() values each: the displacement (m), the velocity (m per fictitious step), the out-of-
  /// balance force F = f_ext - f_int (N) at u and at the iterate before, the inverse fictitious mass.
  std::vector<double> u, v, f, f_old, inv_lambda;
  std::vector<double> history;       ///< the history rows so far (History::values)
};

/// ADR's state between load levels: the fictitious mass (from the model's exact stiffness
/// row sums, computed once), the velocities and work vectors. solve_adr runs it over load
/// steps; the load-path solvers (LBC) call balance() once per balance round.
class AdrRelaxation {
 public:
  AdrRelaxation(Model& model, const AdrOptions& options, Progress* progress = nullptr);
  /// Relaxes u, from rest, to equilibrium under `loading` at factor s. Iterations count
  /// into rep (and stop at options.max_iterations over all calls); rep.residual and
  /// rep.displacement_change are the last ones. after_iteration (if set) runs after each
  /// iteration's force evaluation. Returns whether it converged; throws SolveError on NaN.
  bool balance(const Loading& loading, double s, std::vector<double>& u, SolveReport& rep,
               const Observer& observe = {}, const std::function<void()>& after_iteration = {});
  /// The progress sample's load-step fields (for the bar).
  void set_load_step(int step, int steps) { sample_.load_step = step, sample_.load_steps = steps; }
  /// Hands the state to `checkpoints` at the end of every iteration it is due (counted in
  /// rep.iterations over all balances).
  void set_checkpoints(const Checkpoints<AdrState>& checkpoints) { checkpoints_ = checkpoints; }
  /// The next balance() continues the iterations of `state` (its u is balance's u, its load
  /// factor balance's s) instead of starting from rest; rep's counters are the caller's to set.
  void resume(const AdrState& state);
  /// After the model changed (bonds broke: a refreshed row can be stiffer than before): the
  /// density of each dof k becomes the larger of row_sums[k] / 4 and its density before the
  /// first change (so it depends on the model now, not on the changes' order: a resumed run
  /// gets the same; a detached dof, a zero row, keeps its density).
  void raise_density(const std::vector<double>& row_sums);
  /// The residual is relative to the larger of the load norm and `norm` (N): a body that has
  /// broken apart under displacement control carries no load, and its residual is measured
  /// against the load it carried before (a load path with bond breaking passes its largest
  /// reaction norm so far). 0, the default, leaves the load norm alone.
  void set_load_floor(double norm) { load_floor_ = norm; }
  /// With `on`, the damping is the smaller of the Rayleigh quotient's over u (the seed's) and
  /// its over the balance's own correction, u minus u at its start: late in a softening
  /// separation the correction's slow mode is far softer than the body's stretch, and the
  /// quotient over u overdamped it (solve_load_path turns it on for softening bonds;
  /// docs/theory.md, "Softening bonds").
  void damp_by_correction(bool on) { by_correction_ = on; }

 private:
  /// Appends the supports' reactions at the last force evaluation to the history's last row.
  void add_reactions(const Loading& loading, double s, History& history);
  AdrState state(const std::vector<double>& u, double r, double du, double c, const SolveReport& rep) const;
  Model& model_;
  AdrOptions opt_;
  Progress* progress_;
  ProgressSample sample_;
  std::vector<double> inv_lambda_, v_, f_, f_old_, fint_, last_good_;
  std::vector<double> first_inv_lambda_;  // before raise_density's first call
  double load_floor_ = 0.0;
  bool by_correction_ = false;
  Checkpoints<AdrState> checkpoints_;
  bool resuming_ = false;
  double resume_r_ = 0.0, resume_du_ = 0.0, resume_c_ = 0.0;
};

/// Solves f_int(u) = s * f_ext with u = s * u_bar on the constrained dofs, for
/// s = 1/n, 2/n, ..., 1. Fictitious density lambda_ii = 1/4 sum_j |K_ij| (dt = 1) from the
/// model's exact row sums; adaptive damping from the local Rayleigh quotient.
/// The load norm is the larger of |f_ext| and the norm of the reactions at the constrained
/// dofs, so displacement-driven scenes are measured too. When the loading has supports, each
/// history row ends with their reactions (Loading::reaction_columns, Loading::reactions).
/// On NaN or Inf it stops with report.failure set and converged false, leaving in u the
/// last state (checked every 100 iterations) whose force was finite.
/// `checkpoints` receives the whole state when due; with `resume` (such a state) the solve
/// continues from it, and ends with the u, report and history the uninterrupted solve would.
SolveReport solve_adr(Model& model, const Loading& loading, const AdrOptions& options,
                      std::vector<double>& u, Progress* progress = nullptr,
                      const Observer& observe = {}, const Checkpoints<AdrState>& checkpoints = {},
                      const AdrState* resume = nullptr);

}  // namespace perinom

#pragma once
/// @file Velocity Verlet for dynamics (THEORY sec. 8; seed 002 eq. 99-100).
#include <cstdint>
#include <functional>

#include "perinom/core/error.hpp"
#include "perinom/core/progress.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/models/model.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/model_changes.hpp"

namespace perinom {

struct VerletOptions {
  double dt = 0.0;              ///< time step (s); 0 picks safety * the stable step
  double safety = 0.8;          ///< fraction of the stable step when dt = 0
  std::int64_t steps = 1000;
  double ramp_time = 0.0;       ///< loads ramp linearly to full over this time (s); 0: at once
  std::int64_t history_every = 10;
  /// The energy-balance guard: at every history row, the run stops (SolveError, exit 3)
  /// when |E - E0 - W| > energy_tolerance * max(max W, max E) + R, with E the kinetic plus
  /// strain energy, E0 its initial value, W the work of the loads and of the constraints so
  /// far, the maxima over the rows so far, and R the rounding floor of the state: eps
  /// omega_max^2 sum_k m_k u_k^2 / 2, a bound of the size of the terms the strain energy and
  /// the constraints' work sum (omega_max = 2 / the stable step). Verlet's own energy error at a
  /// stable step is a few percent at most; a discrete problem with negative or complex
  /// eigenvalues (the improved and strong formulations) gains energy no load supplied.
  bool energy_check = true;
  double energy_tolerance = 0.5;
};

/// What solve_verlet carries from one step to the next, taken at the end of a step: with it
/// the integration continues bit for bit (solve_verlet's `resume`).
struct VerletState {
  std::int64_t step = 0;  ///< steps done
  double time = 0.0;      ///< t after them (s), summed step by step as the loop does
  double dt = 0.0;        ///< the step it integrates with (s)
  /// The energy balance: external work so far (J), the energy at step 0, the largest energy
  /// and the largest |work| of the history rows so far.
  double work = 0.0, e0 = 0.0, e_max = 0.0, w_max = 0.0;
  /// dofs() values each: displacement (m), velocity (m/s), acceleration (m/s^2) and the
  /// internal force (N) at u.
  std::vector<double> u, v, a, fint;
  std::vector<double> multipliers;  ///< Galerkin supports that move: their multipliers at u (N), else empty
  std::vector<double> history;      ///< the history rows so far (History::values)
  /// A run whose model changes (ModelChanges; otherwise all zero and empty): the stable step
  /// it started with (s) and the ratio of its first dt to it, the changes made and the energy they released (J), the steps that
  /// made changes and those that lowered dt, and ModelChanges::save().
  double stable_time_step = 0.0, dt_per_stable = 0.0;
  double changed = 0.0, released = 0.0;
  std::int64_t changing_steps = 0, step_reductions = 0;
  std::vector<double> changes;
};

/// No time step to integrate with: dt = 0 asked for safety times the stable step, and that is
/// 0 or not finite (a mass too small or a stiffness too large for doubles). Bad input, alike
/// on every rank (the stable step is the ranks' least); the scene layer names its keys.
class StableStepError : public InputErrorOnEveryRank {
 public:
  using InputErrorOnEveryRank::InputErrorOnEveryRank;
};

/// The stable step 2 / omega_max, with omega_max^2 bounded by max_i sum_j |K_ij| / m_i
/// (Gershgorin on M^-1 K with the model's exact row sums).
double stable_time_step(const Model& model);

/// Integrates M u'' = s(t) f_ext - f_int(u) from the given u, v (constrained dofs follow
/// s(t) u_bar). The history records time, kinetic, strain and external-work energies; the
/// external work is that of the loads on the free dofs plus that of the constraints (their
/// reactions f_int times the constrained dofs' motion, zero for fixed supports), each
/// trapezoidal in time, so kinetic + strain - external work stays at its initial value.
/// On NaN or Inf, or when the energy balance fails (VerletOptions::energy_check), it stops
/// with report.failure set and converged false, leaving in u the last state kept (every 100
/// steps, after that step's energy check) whose force was finite.
/// `checkpoints` receives the whole state when due; with `resume` (such a state) the
/// integration continues from it, and ends with the u, v, report and history the
/// uninterrupted one would.
/// With `changes` the history gains the columns broken_bonds and released_energy; such a run
/// is resumed only when the changes can save and restore themselves (ModelChanges::save):
/// restore() puts the model back first, the stable step and the counts come from the state.
SolveReport solve_verlet(Model& model, const Loading& loading, const VerletOptions& options,
                         std::vector<double>& u, std::vector<double>& v,
                         Progress* progress = nullptr, const Observer& observe = {},
                         const Checkpoints<VerletState>& checkpoints = {}, const VerletState* resume = nullptr,
                         const ModelChanges* changes = nullptr);

}  // namespace perinom

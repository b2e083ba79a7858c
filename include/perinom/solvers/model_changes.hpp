#pragma once
/// @file Irreversible changes of a model during a solve (bonds that break), as the solvers
/// drive them: Verlet after its steps (verlet.hpp), a load path after its balances
/// (load_path.hpp). What changes and how is the caller's (fracture/bond_breaking.hpp).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "perinom/core/types.hpp"

namespace perinom {

/// What ModelChanges::apply made: how many changes, and the strain energy they released.
struct ChangesMade {
  std::size_t count = 0;
  double released = 0.0;  ///< J, at the state the changes were made at
};

/// Irreversible changes of the model during a run (bonds that break: fracture/bond_breaking.hpp).
/// Verlet: every `every` steps, at the end of the step (u and v updated on the model as it was),
/// find(u) counts those due at u; when any are, apply(u, f) makes them, with f the internal
/// force at u the step took last, and leaves in f the changed model's force at u, which the
/// next step starts from. It returns the strain energy the changes released at u (a history
/// column, so that kinetic + strain + released - external work stays at its initial value).
/// The stable step follows the changes when stable_step is given (below).
struct ModelChanges {
  /// Called at the end of a step, at the u whose internal force the step evaluated last.
  /// (A load path, solve_load_path, calls it after each balance, at the balanced u, after
  /// evaluating the force there, and apply() with that force; it balances again after a
  /// change, until find() finds none.)
  std::function<std::size_t(const double* u)> find;
  std::function<ChangesMade(const double* u, double* f)> apply;
  std::int64_t every = 1;
  /// Optional: the model's stable time step now (called once before the first step, in place
  /// of stable_time_step(model), and after each apply()). The run keeps the ratio of its
  /// step to the stable step it started with: when a change lowers the stable step, dt
  /// follows it down (never up again), so broken bonds cannot make the scheme unstable.
  std::function<double()> stable_step;
  /// Optional, both or neither: what the changes are so far, as numbers (a checkpoint's
  /// VerletState::changes), and the model put back into such a state (the model as built
  /// before). Without them a run with changes is not resumed.
  std::function<std::vector<double>()> save;
  std::function<void(const std::vector<double>&)> restore;
  /// Optional: the stiffness row sums per dof (sum_j |K_kj|) of the model now, once
  /// stable_step() has been called (apply() keeps them up to date). A load path raises ADR's
  /// density with them after each change (AdrRelaxation::raise_density).
  std::function<const std::vector<double>&()> row_sums;
  /// The model dissipates energy between changes too (softening bonds, whose state find()
  /// commits): a load path's energy account (EnergyLedger) recounts after every step.
  bool dissipates = false;
  /// Optional: the particles the changes have detached so far (sorted; held by nothing but
  /// what the changes left, e.g. softening bonds). A load step that fails to balance says
  /// how much of its residual is theirs and how much the rest of the body's.
  std::function<const std::vector<ParticleId>&()> detached;
};

}  // namespace perinom

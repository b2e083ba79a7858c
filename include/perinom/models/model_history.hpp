#pragma once
/// @file What a load path drives in a model whose answer depends on its past (plasticity):
/// trial states evaluated from committed ones, a commit per load step, the flags of the
/// loading-balance-correction scheme, and the committed state as numbers for checkpoints.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace perinom {

/// How internal_force evaluates the trial states until the next set_history_mode:
///   flagged:    unflagged particles answer with the elastic trial from their committed state,
///               flagged ones with the return map (loading-balance-correction);
///   return_map: every particle answers with the return map from its committed state.
enum class HistoryMode { flagged, return_map };

/// The committed history as plain numbers (a checkpoint's record): `values` holds
/// ModelHistory::values_per_particle() reals per particle, `flags` one per particle.
struct HistoryState {
  std::vector<double> values;
  std::vector<std::uint8_t> flags;
};

/// The states of a law with history as a load path drives them (PlasticPoints implements
/// it; PointwiseLaw::history() hands it out). A model adds the evaluation at u (ModelHistory).
class LawHistory {
 public:
  virtual ~LawHistory() = default;
  virtual void set_history_mode(HistoryMode mode) = 0;
  /// Flags every unflagged particle whose trial state violates the yield condition by more
  /// than `tolerance` (relative to the yield stress); returns how many were flagged now.
  virtual std::size_t flag_violations(double tolerance) = 0;
  /// The committed equivalent plastic strain per particle (the load path counts the
  /// particles yielding in a step, xi grew, and plastic, xi > 0).
  virtual std::vector<double> history_variable() const = 0;
  /// The committed state and flags as numbers, and back (the trial states equal to it, as
  /// after a commit). restore_history throws std::invalid_argument for a state of another size.
  virtual std::size_t values_per_particle() const = 0;
  virtual HistoryState save_history() const = 0;
  virtual void restore_history(const HistoryState& state) = 0;
  /// Back to the virgin state: no plastic strain, no flag.
  virtual void reset_history() = 0;
};

/// Implemented by models with history (CorrespondenceModel with a law that has one);
/// Model::history() returns nullptr for the others. solve_load_path needs nothing else.
class ModelHistory : public LawHistory {
 public:
  /// Evaluates every particle at u (m) by the current mode and commits the result.
  virtual void commit(const double* u) = 0;
  /// Commits the trial states the last internal_force kept, without evaluating again (the
  /// explicit scheme that commits after every iteration).
  virtual void commit_trial() = 0;
  /// Called as each load step begins, from the committed state it starts at. A model whose
  /// operators follow that state (a secant stabilization) sets them here, not at commit, so
  /// a balanced state keeps the force it was balanced with until the next step starts (its
  /// reactions and equilibrium are the balance's).
  virtual void begin_step() {}
};

}  // namespace perinom

#pragma once
/// @file The energy account of an elastic body that breaks on a load path: the work the
/// loads have done on it and the energy its breaks dissipated.
#include <vector>

#include "perinom/models/model.hpp"

namespace perinom {

/// Keeps W, the external work, and D = W - E(u), the energy dissipated, over the balanced
/// states of a load path. Between breaks the body is linear elastic with a symmetric
/// stiffness (damage needs the classical formulation), so from the last committed state to
/// a step's first balance W grows by the trapezoid 0.5 (f_0 + f_1).(u_1 - u_0) of the
/// internal forces, which is exact, and D does not change. The later balances of a step are
/// at the step's loads: where u moves the force at a balanced state is the applied load
/// (the reduced residual vanishes), so W grows by f.(u - u_1) at the step's last balance.
/// Only a step that broke bonds pays for E(u), one energy evaluation. Exact up to the
/// balances' tolerance; not for plastic bodies (no such ledger is kept there).
class EnergyLedger {
 public:
  /// At the state u (balanced, or at rest) with the account so far.
  EnergyLedger(Model& model, const std::vector<double>& u, double work, double dissipated)
      : f_last_(u.size()), work_(work), dissipated_(dissipated) {
    model.internal_force(u.data(), f_last_.data());
    u_last_ = u;
  }

  /// After each balance of a step, at the balanced u with its internal force f; `first`
  /// for the step's first balance (before this step broke anything).
  void balanced(const std::vector<double>& u, const std::vector<double>& f, bool first) {
    if (!first) return;
    for (std::size_t k = 0; k < u.size(); ++k) work_ += 0.5 * (f_last_[k] + f[k]) * (u[k] - u_last_[k]);
    u_first_ = u;
  }

  /// At the step's last balance (nothing more due): u, f as there; `broke` if the step
  /// broke bonds (or the model dissipates without breaks: ModelChanges::dissipates; then
  /// the first balance's trapezoid is exact only to the step's curvature of the force).
  void commit(Model& model, const std::vector<double>& u, const std::vector<double>& f, bool broke) {
    if (broke) {
      for (std::size_t k = 0; k < u.size(); ++k) work_ += f[k] * (u[k] - u_first_[k]);
      dissipated_ = work_ - model.energy(u.data());
    }
    f_last_ = f;
    u_last_ = u;
  }

  double work() const { return work_; }
  double dissipated() const { return dissipated_; }

 private:
  std::vector<double> f_last_, u_last_, u_first_;
  double work_ = 0.0, dissipated_ = 0.0;
};

}  // namespace perinom

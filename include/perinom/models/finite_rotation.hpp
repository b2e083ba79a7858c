#pragma once
/// @file Finite rotation around a law in rate form (seed 000 sec. 2.1, THEORY sec. 3): a
/// PointwiseLaw that keeps the deformation gradient F = I + grad u of every particle and
/// hands the law it wraps (an IncrementalLaw) the unrotated strain increment of each step.
///
/// Over a step from the committed F_n to F the increment is R_m^T sym(L) R_m with
/// L = (F - F_n) F_m^-1 and R_m the rotation of the midpoint F_m = (F + F_n)/2: zero for any
/// rigid rotation, since L is then the Cayley transform of the rotation, which is skew. The
/// law works on the unrotated stress sigma_u; the Cauchy stress is R sigma_u R^T with R from
/// the polar decomposition of F, and the model receives P = J sigma F^-T. In 2-D (plane
/// strain) F_zz = 1 with no out-of-plane shear. The tangent for Newton is the closed-form
/// chain rule through all of these, the polar rotations' derivatives included
/// (finite_rotation_tangent.cpp).
///
/// History: the wrapped law's, with F appended (a checkpoint holds the law's values per
/// particle, then the 9 of F); the trial F is kept with the law's trial state and committed
/// with it.
#include <memory>

#include "perinom/models/incremental_law.hpp"
#include "perinom/models/model_history.hpp"
#include "perinom/models/per_particle_law.hpp"
#include "perinom/models/pointwise_law.hpp"

namespace perinom {

/// small_strain: the law reads sym(grad u) itself; finite_rotation: FiniteRotationLaw.
enum class Kinematics { small_strain, finite_rotation };

class FiniteRotationLaw final : public PerParticleLaw<FiniteRotationLaw>, public LawHistory {
 public:
  /// Wraps `law` (which must keep a history) for a model in `dim` dimensions; F = I.
  FiniteRotationLaw(std::unique_ptr<IncrementalLaw> law, int dim);

  IncrementalLaw& inner() { return *law_; }
  const IncrementalLaw& inner() const { return *law_; }

  int dim() const override { return dim_; }
  std::size_t size() const override { return law_->size(); }
  bool has_history() const override { return true; }
  using PerParticleLaw::cauchy;
  void commit() override;
  LawHistory* history() override { return this; }
  std::size_t memory_bytes() const override;
  /// "stress" (the Cauchy stress), then the wrapped law's state fields.
  std::vector<LawField> fields() const override;
  void field(const std::string& name, const double* H, std::vector<double>& values) const override;

  /// Particle i at grad u = H: P (d x d) by the law's mode, kept as the trial state.
  void stress(std::size_t i, const double* H, double* P);
  /// dP/dH (d^4) of the return map at H from the committed state.
  void tangent(std::size_t i, const double* H, double* C) const;
  /// The 3 x 3 Cauchy stress of the return map at H from the committed state, nothing kept.
  void cauchy(std::size_t i, const double* H, double* sigma) const;
  /// The wrapped law's stored energy density of the kept trial state (J/m^3).
  double stored_energy(std::size_t i) const { return law_->stored_energy(i); }

  // LawHistory: the wrapped law's, with F after its values.
  void set_history_mode(HistoryMode mode) override { inner_history().set_history_mode(mode); }
  std::size_t flag_violations(double tolerance) override { return inner_history().flag_violations(tolerance); }
  std::vector<double> history_variable() const override;
  std::size_t values_per_particle() const override;
  HistoryState save_history() const override;
  void restore_history(const HistoryState& state) override;
  void reset_history() override;

 private:
  /// F = I + grad u (3 x 3) of H (d x d), and the unrotated increment from the committed F.
  void increment(std::size_t i, const double* H, double* F, double* deps) const;
  LawHistory& inner_history() const;

  std::unique_ptr<IncrementalLaw> law_;
  int dim_;
  std::vector<double> committed_F_, trial_F_;  ///< N x 9
};

}  // namespace perinom

#pragma once
/// @file The assembled Jacobian of the static residual, for Newton and direct solves.
#include <cstdint>
#include <vector>

#include "perinom/models/tangent_model.hpp"
#include "perinom/models/loading.hpp"

namespace perinom {

/// A square sparse matrix in CSR form with 64-bit indices (SUNDIALS' sunindextype).
struct CsrMatrix {
  std::int64_t rows = 0;
  std::vector<std::int64_t> row_ptr{0}, col;
  std::vector<double> val;
  std::size_t memory_bytes() const;
};

/// The residual of a static load step at load factor s, with constraints on the particles:
///   R_k = f_int(u)_k - s f_ext_k                                  (free dofs)
///   R_k = kappa (u_k - s u_bar)                                   (constrained dofs)
/// With face-located constraints E u = t (row k: 1/scale_k on its dof, coef_c on the coupled
/// ones) the unknowns are u and one multiplier y_k per constraint (dofs() = N d + constraints):
///   R_k     = f_int(u)_k - s f_ext_k + kappa sum_l E_lk y_l        (every dof)
///   R_(N d + l) = kappa (E_l u - t_l(s))
/// the Galerkin form: the reaction kappa E^T y spreads over every particle a constraint reads,
/// and the Jacobian [K, kappa E^T; kappa E, 0] is symmetric when K is.
/// kappa is the largest stiffness diagonal, so that constraint rows are scaled like the
/// others (pivoting by magnitude then works), and the Jacobian dR/du. The pattern is built
/// once (symbolic), the values are refilled in place (numeric), so a sparse LU keeps its
/// symbolic analysis across iterations and load steps.
class StaticSystem {
 public:
  /// Any model that visits its tangent rows: correspondence elasticity and plasticity, the
  /// thin plate.
  StaticSystem(TangentModel& model, const Loading& loading);

  /// The unknowns: the model's dofs, then the multipliers (face-located constraints only).
  std::size_t dofs() const { return static_cast<std::size_t>(J_.rows); }
  std::size_t multipliers() const { return m_; }
  /// R(u) at load factor s (u holds dofs() values).
  void residual(const double* u, double s, double* R);
  /// Refills the Jacobian's values at u (the pattern never changes); u may be null for a
  /// model whose tangent does not depend on u.
  void assemble(const double* u);
  const CsrMatrix& jacobian() const { return J_; }
  /// max(|s f_ext|, |reactions at u|): the norm a relative residual is measured by (as in ADR).
  double load_norm(const double* u, double s);

 private:
  void fill(bool symbolic);
  TangentModel& model_;
  const Loading& loading_;
  std::vector<std::int64_t> constraint_of_;  // dof -> index into loading.fixed, or -1
  std::size_t n_ = 0, m_ = 0;                // model dofs; multipliers
  // E^T by dof (face-located constraints): constraints et_k_[et_ptr_[r] ..) with values et_val_.
  std::vector<std::int64_t> et_ptr_, et_k_;
  std::vector<double> et_val_;
  double kappa_ = 1.0;
  CsrMatrix J_;
  std::vector<double> fint_;
};

}  // namespace perinom

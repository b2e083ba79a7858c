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

/// The residual of a static load step at load factor s:
///   R_k = f_int(u)_k - s f_ext_k                                  (free dofs)
///   R_k = kappa (u_k / scale + sum_c coef_c u_c - s u_bar)        (constrained dofs)
/// kappa is the largest stiffness diagonal, so that constraint rows are scaled like the
/// others (pivoting by magnitude then works), and the Jacobian dR/du. The pattern is built
/// once (symbolic), the values are refilled in place (numeric), so a sparse LU keeps its
/// symbolic analysis across iterations and load steps.
class StaticSystem {
 public:
  /// Any model that visits its tangent rows: correspondence elasticity and plasticity, the
  /// thin plate.
  StaticSystem(TangentModel& model, const Loading& loading);

  std::size_t dofs() const { return static_cast<std::size_t>(J_.rows); }
  /// R(u) at load factor s.
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
  double kappa_ = 1.0;
  CsrMatrix J_;
  std::vector<double> fint_;
};

}  // namespace perinom

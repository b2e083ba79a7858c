#pragma once
/// @file The operator-energy (hourglass) stabilization of the second-order fit for a scalar
/// field (THEORY sec. 6, seed 002 eq. 35-39).
#include <functional>
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
#include "perinom/operators/scalar_csr.hpp"

namespace perinom {

/// W_s = 1/2 sum_i cv_i sum_j wv_ij z_ij^2 with z_ij = f_j - f_i - p_ij . D_i, p_ij the
/// quadratic basis of xi_ij and D_i = (grad f, Hess f)_i from the operator (zero for quadratic
/// f). Because D_i is the weighted least-squares fit of the f_j - f_i, the derivative of
/// W_s through D_i vanishes (as for the first-order S, stabilization.hpp), so
///   (dW_s/df)_l = sum_{i in H'_l} cv_i wv_il z_il - cv_l sum_j wv_lj z_lj,
/// one bond pass in row order and one in dual-support order. The matrix is S = sum_i cv_i
/// E_i^T (W_i - W_i P_i^T K_i P_i W_i) E_i, E_i the differences f_j - f_i (docs/theory.md).
/// Storage: w V per bond in dual order (row order is the operator's), the positions, and
/// sum_j wv_ij p_ij per particle.
class SecondOrderStabilization {
 public:
  /// cv[i] >= 0 per particle (0: no stabilization energy at i; detached particles get 0);
  /// op (order 2 with its Hessian) must outlive this object. Dead bonds count with w V = 0.
  SecondOrderStabilization(const PointCloud& cloud, const NonlocalOperator& op, std::vector<double> cv);

  /// out += dW_s/df for a scalar field f, given its gradient (N x d) and Hessian (N x m).
  void add_force(const double* f, const double* grad, const double* hess, double* out);
  /// W_s(f).
  double energy(const double* f, const double* grad, const double* hess) const;
  /// Row r of S: add(column, value) for each contribution (columns may repeat).
  void add_row(std::size_t r, const std::function<void(ParticleId, double)>& add) const;
  /// After op.refresh_rows(rows): cv_i = cv[i] (the new coefficients, all particles), the
  /// w V of those rows' bonds in both orders, and their sums sum_j wv_ij p_ij.
  void refresh_rows(const std::vector<ParticleId>& rows, const std::vector<double>& cv);

  std::size_t memory_bytes() const;

 private:
  double z(std::size_t i, std::size_t j, const double* f, const double* grad, const double* hess) const;
  void basis(std::size_t i, std::size_t j, double* p) const;
  int dim_, nb_;
  const NonlocalOperator* op_;
  /// w_ij V_j of bond k, zero when it is dead.
  double wv(Offset k) const { return op_->graph().alive(k) ? (*wv_)[k] : 0.0; }
  std::vector<double> x_, cv_;
  const std::vector<double>* wv_;  // the operator's w_ij V_j (row order)
  std::vector<double> t_wv_, b_;   // b_: sum_j wv_ij p_ij (nb per particle)
  std::vector<double> r_;                       // workspace: cv_i sum_j wv_ij z_ij
};

/// S assembled (symmetric, positive semi-definite, zero on quadratic fields), row by row from
/// add_row: the form the second-order correspondence model applies to each displacement
/// component (S (x) I_d), after which the fit's Hessian weights are no longer needed.
ScalarCsr assemble_second_order_stabilization(const SecondOrderStabilization& S, std::size_t particles);
/// After S.refresh_rows(rows): the rows of the assembled S they change (stabilization_rows).
void refresh_second_order_stabilization(ScalarCsr& A, const SecondOrderStabilization& S, const BondGraph& graph,
                                        const std::vector<ParticleId>& rows);

/// cv_i = C_hg D area_i / (sum_j wv_ij |xi_ij|^4 / 4): W_s is then about C_hg times the bending
/// energy 1/2 D |kappa|^2 area_i of a curvature the fit misses (z ~ kappa |xi|^2 / 2).
/// area_i = 0 gives 0.
std::vector<double> second_order_stabilization_coefficients(const PointCloud& cloud, const NonlocalOperator& op,
                                                            double c_hg, double rigidity,
                                                            const std::vector<double>& area);

}  // namespace perinom

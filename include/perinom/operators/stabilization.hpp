#pragma once
/// @file The zero-energy-mode stabilization of a nonlocal fit of order 1 or 2 (THEORY sec. 4
/// and 6; seed 002 eq. 35-39), matrix-free: one bond code for both orders.
#include <functional>
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
#include "perinom/operators/row_accumulator.hpp"
#include "perinom/operators/scalar_csr.hpp"

namespace perinom {

/// cv_i >= 0 for particle i (0: no stabilization energy at i). Read at construction and, for
/// the refreshed rows, after the operators' refresh_rows (it may read them); thread-safe.
using StabilizationScale = std::function<double(std::size_t)>;

/// W_s = 1/2 sum_i cv_i sum_j wv_ij |z_ij|^2 over a field u of C components, with
///   z_ij = u_j - u_i - D_i p_ij,
/// p_ij the fit's basis of xi_ij = x_j - x_i (order 1: xi; order 2: xi and its quadratic
/// terms xi_a xi_b, 1/2 xi_a^2 on the diagonal), D_i the fit's derivatives of u at i
/// (gradient, and Hessian for order 2; zero z for fields of the fit's order), wv_ij = w_ij V_j
/// (zero for a dead bond). Because D_i is the weighted least-squares fit of the u_j - u_i,
/// the derivative of W_s through D_i vanishes up to B_i = sum_j beta_ij z_ij (x) xi_ij
/// (beta_ij = cv_i wv_ij), zero for the fit's own D_i, kept for a first-order G whose rows
/// differ from the fit:
///   S u = dW_s/du = G^T(-B) + d,   d_l = sum_{i in H'_l} beta_il z_il - r_l,
///   r_i = sum_j beta_ij z_ij,
/// one bond pass in row order (bond_terms) and one in dual-support order (add_direct).
/// S = sum_i cv_i E_i^T (W_i - W_i P_i^T K_i^-1 P_i W_i) E_i (E_i the differences u_j - u_i),
/// applied to each component (S (x) I_C); its rows come from that closed form, one row at a
/// time (add_row; docs/theory.md). Storage: w V per bond in both orders, the positions, cv.
class Stabilization {
 public:
  /// `fit` (order 1, or order 2 with its Hessian) must outlive this object; dead bonds count
  /// with w V = 0, a detached particle with cv = 0.
  Stabilization(const PointCloud& cloud, const NonlocalOperator& fit, StabilizationScale scale);
  /// The first-order form: cv_i = modulus / tr K_i V_i from G's shape tensors (shape_scale).
  Stabilization(const PointCloud& cloud, const NonlocalOperator& G, double modulus);

  /// The fit's order, and the size of its basis p (d, or d + d(d+1)/2).
  int order() const { return nb_ == dim_ ? 1 : 2; }
  int basis_size() const { return nb_; }

  /// Row pass for u (N x C) with the fit's gradient grad (N x C x d) and, order 2, Hessian
  /// hess (N x C x d(d+1)/2; nullptr for order 1): r (N x C), and B (N x C x d) when given.
  void bond_terms(const double* u, int components, const double* grad, const double* hess, double* B,
                  double* r) const;
  /// Dual pass: out_l += sum_{i in H'_l} beta_il z_il - r_l.
  void add_direct(const double* u, int components, const double* grad, const double* hess, const double* r,
                  double* out) const;
  /// out += S u for derivatives that are the fit's own (B = 0): both passes.
  void add_force(const double* u, int components, const double* grad, const double* hess, double* out);
  /// W_s(u), the same bits for any thread count.
  double energy(const double* u, int components, const double* grad, const double* hess) const;
  /// Order 1, for a vector field (C = d) with H = grad u (N x d x d).
  void bond_terms(const double* u, const double* H, double* B, double* r) const {
    bond_terms(u, dim_, H, nullptr, B, r);
  }
  void add_direct(const double* u, const double* H, const double* r, double* out) const {
    add_direct(u, dim_, H, nullptr, r, out);
  }

  /// Adds row i of S to acc: the value to acc.at(j)[k * (copies + 1)] for k < copies (copies
  /// = 1 for the scalar S, d for the diagonal of d x d blocks); or to add(j, value) (columns
  /// may repeat).
  void add_row(std::size_t i, RowAccumulator& acc, int copies) const;
  void add_row(std::size_t i, const std::function<void(ParticleId, double)>& add) const;
  /// After fit.refresh_rows(rows) (distinct rows): cv_i and the w V of those rows' bonds, in
  /// both orders.
  void refresh_rows(const std::vector<ParticleId>& rows);
  /// S0 += sign * the blocks of these centres (centre m's block couples {m} + H_m; S is the
  /// sum of the blocks), within S0's pattern (std::logic_error outside it). Taken with sign
  /// -1 before the fit's and this object's refresh_rows(centres) and +1 after, it updates a
  /// stored S0 by differences: refresh_stabilization's rows to rounding, for the cost of the
  /// refreshed centres' blocks instead of every row they touch.
  void add_blocks(ScalarCsr& S0, const std::vector<ParticleId>& centres, double sign) const;

  /// cv_i of every particle.
  const std::vector<double>& scaled_coefficients() const { return cv_; }
  /// cv_i = factor_i times its value as built (one factor per particle, e.g. the material's
  /// secant stiffness over its elastic one); kept through refresh_rows. The force, energy and
  /// rows then use the scaled values.
  void set_centre_factors(std::vector<double> factor);
  /// w_ij V_j of bond k (row order; zero for a dead bond).
  double bond_weight(Offset k) const { return wv_[k]; }

  std::size_t memory_bytes() const;

 private:
  template <class Add>
  void row(std::size_t i, Add&& add) const;
  /// Row r of centre r's block, and row r of centre i's block for r in H_i (w_ir V_r given).
  template <class Add>
  void centre_row(std::size_t r, Add&& add) const;
  template <class Add>
  void member_row(std::size_t i, std::size_t r, double wv_ir, Add&& add) const;
  void basis_of(std::size_t i, std::size_t j, double* p) const;
  /// The fit's weights a_ik of bond k (gradient, then Hessian: nb values), and -sum_k a_ik.
  const double* fit_weights(Offset k, double* out) const;
  const double* fit_diagonal(std::size_t i, double* out) const;
  void refresh_row(ParticleId i);

  int dim_, nb_;
  const NonlocalOperator* fit_;
  StabilizationScale scale_;
  std::vector<double> x_, cv_;     // positions; cv_i
  std::vector<double> c0_, factor_;  // cv_i as built (scale_, read once: G may change after), its factor
  std::vector<double> wv_, t_wv_;  // w_ij V_j in row order and in dual-support order
  std::vector<double> r_;          // add_force's workspace
};

/// cv_i = modulus / tr K_i V_i, K_i from G's shape tensors (0 for a detached particle or
/// tr K_i <= 0): the correspondence force's scale, modulus = C_hg 2 mu, at either fit order.
StabilizationScale shape_scale(const NonlocalOperator& G, double modulus, std::vector<double> volume);

/// cv_i = C_hg D area_i / (sum_j wv_ij |xi_ij|^4 / 4) over i's live bonds: W_s is then about
/// C_hg times the bending energy 1/2 D |kappa|^2 area_i of a curvature the fit misses
/// (z ~ kappa |xi|^2 / 2) (the thin plate). area_i = 0 gives 0.
StabilizationScale bending_scale(const NonlocalOperator& op, double c_hg, double rigidity, std::vector<double> area);

/// S assembled (symmetric, positive semi-definite, zero on fields of the fit's order), row by
/// row from add_row. For checks, direct solves and the assembled level.
ScalarCsr assemble_stabilization(const Stabilization& S, std::size_t particles);

/// The rows of a stored stabilization that a refresh of these rows of G changes: each row i
/// and its family H_i (centre i's block couples {i} + H_i).
std::vector<ParticleId> stabilization_rows(const BondGraph& graph, const std::vector<ParticleId>& rows);

/// After the fit's and S.refresh_rows(rows): the rows of the stored S they change.
void refresh_stabilization(ScalarCsr& S0, const Stabilization& S, const BondGraph& graph,
                           const std::vector<ParticleId>& rows);

/// c_i = C_hg * 2 mu / tr(K_i) for every particle (0 for a detached one), from G's shape tensors.
std::vector<double> stabilization_coefficients(const NonlocalOperator& G, double c_hg, double mu);

}  // namespace perinom

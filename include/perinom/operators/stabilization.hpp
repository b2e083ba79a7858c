#pragma once
/// @file The zero-energy-mode stabilization S (THEORY sec. 4), matrix-free.
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/families.hpp"
#include "perinom/operators/bond_weights.hpp"
#include "perinom/operators/gradient_operator.hpp"
#include "perinom/operators/row_accumulator.hpp"
#include "perinom/operators/scalar_csr.hpp"

namespace perinom {

/// W_s = 1/2 sum_i sum_j beta_ij |z_ij|^2 with beta_ij = c_i V_i w_ij V_j and
/// z_ij = u_j - u_i - (grad u)_i xi_ij; S u = dW_s/du is linear in u, S = S0 (x) I_d.
///
/// Applied without storing S (its pattern couples particles two horizons apart, about 75
/// bytes per bond in 3-D): with B_i = sum_j beta_ij z_ij (x) xi_ij and r_i = sum_j beta_ij z_ij,
///   S u = G^T(-B) + d,   d_l = sum_{i in H'_l} beta_il z_il - r_l,
/// so the -B part rides along with the weak-form product G^T (V . P) the model makes anyway,
/// and only the two bond passes below are added. Storage: w V per bond in both orders.
/// Rows of S0 (for tangents) come from the closed form of particle i's block,
/// M_i = c_i V_i (D_i - A_i K_i^-1 A_i^T) (docs/theory.md), one row at a time.
class Stabilization {
 public:
  /// coefficient[i] = c_i = C_hg 2 mu / tr K_i (Pa/m^5); G must outlive this object.
  Stabilization(const PointCloud& cloud, const Families& families, const BondWeights& weights,
                const GradientOperator& G, const std::vector<double>& coefficient);

  /// Row pass: B (N x d x d) and r (N x d) from u (N x d) and H = grad u (N x d x d).
  void bond_terms(const double* u, const double* H, double* B, double* r) const;
  /// Dual pass: out_l += sum_{i in H'_l} beta_il z_il - r_l.
  void add_direct(const double* u, const double* H, const double* r, double* out) const;
  /// Adds row i of S0 to acc: value to acc.at(j)[k * (copies + 1)] for k < copies (copies = 1
  /// for the scalar S0, d for the diagonal of d x d blocks).
  void add_row(std::size_t i, RowAccumulator& acc, int copies) const;

  std::size_t memory_bytes() const;

 private:
  int dim_;
  const GradientOperator* G_;
  std::vector<double> x_, cv_;      // positions; c_i V_i
  std::vector<double> wv_, t_wv_;   // w_ij V_j in row order and in dual-support order
};

/// S0 assembled (symmetric, positive semi-definite, zero on linear fields), row by row from
/// Stabilization::add_row. For checks and direct solves; the explicit path never stores it.
ScalarCsr assemble_stabilization(const Stabilization& S, std::size_t particles);

/// c_i = C_hg * 2 mu / tr(K_i) for every particle.
std::vector<double> stabilization_coefficients(const BondWeights& weights, int dim, double c_hg,
                                               double mu);

}  // namespace perinom

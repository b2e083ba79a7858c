#pragma once
/// @file The zero-energy-mode stabilization S (THEORY sec. 4), matrix-free.
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
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
/// Dead bonds of G's graph count with w V = 0; a detached particle has c_i = 0.
class Stabilization {
 public:
  /// c_i = modulus / tr K_i (Pa/m^5) from G's shape tensors, modulus = C_hg 2 mu; G (a
  /// first-order operator from a fit) must outlive this object.
  Stabilization(const PointCloud& cloud, const NonlocalOperator& G, double modulus);

  /// Row pass: B (N x d x d) and r (N x d) from u (N x d) and H = grad u (N x d x d).
  void bond_terms(const double* u, const double* H, double* B, double* r) const;
  /// Dual pass: out_l += sum_{i in H'_l} beta_il z_il - r_l.
  void add_direct(const double* u, const double* H, const double* r, double* out) const;
  /// Adds row i of S0 to acc: value to acc.at(j)[k * (copies + 1)] for k < copies (copies = 1
  /// for the scalar S0, d for the diagonal of d x d blocks).
  void add_row(std::size_t i, RowAccumulator& acc, int copies) const;
  /// After G.refresh_rows(rows) (distinct rows): c_i and the w V of those rows' bonds, in both orders.
  void refresh_rows(const std::vector<ParticleId>& rows);

  /// c_i V_i of every particle.
  const std::vector<double>& scaled_coefficients() const { return cv_; }
  /// w_ij V_j of bond k (row order; zero for a dead bond).
  double bond_weight(Offset k) const { return wv_[k]; }

  std::size_t memory_bytes() const;

 private:
  void refresh_coefficient(std::size_t i, const std::vector<double>& volume);
  int dim_;
  double modulus_;
  const NonlocalOperator* G_;
  std::vector<double> x_, cv_;      // positions; c_i V_i
  std::vector<double> wv_, t_wv_;   // w_ij V_j in row order and in dual-support order
  std::vector<double> volume_;
};

/// S0 assembled (symmetric, positive semi-definite, zero on linear fields), row by row from
/// Stabilization::add_row. For checks and direct solves; the explicit path never stores it.
ScalarCsr assemble_stabilization(const Stabilization& S, std::size_t particles);

/// The rows of a stored stabilization (S0, or the second-order S) that a refresh of these
/// rows of G changes: each row i and its family H_i (centre i's block couples {i} + H_i).
std::vector<ParticleId> stabilization_rows(const BondGraph& graph, const std::vector<ParticleId>& rows);

/// After G.refresh_rows and S.refresh_rows(rows): the rows of the stored S0 they change.
void refresh_stabilization(ScalarCsr& S0, const Stabilization& S, const BondGraph& graph,
                           const std::vector<ParticleId>& rows);

/// c_i = C_hg * 2 mu / tr(K_i) for every particle (0 for a detached one), from G's shape tensors.
std::vector<double> stabilization_coefficients(const NonlocalOperator& G, double c_hg, double mu);

}  // namespace perinom

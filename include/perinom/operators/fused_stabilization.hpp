#pragma once
/// @file The zero-energy-mode stabilization S applied inside the two products of G.
#include <optional>
#include <utility>
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/operators/nonlocal_operator.hpp"

namespace perinom {

/// S u = dW_s/du for W_s = 1/2 sum_i sum_j beta_ij |z_ij|^2 (THEORY sec. 4), with
/// beta_ij = cv_i wv_ij (cv_i = c_i V_i, wv_ij = w_ij V_j) and z_ij = u_j - u_i - H_i xi_ij.
///
/// Because g_ij = wv_ij K_i^-1 xi_ij with K_i = sum_j wv_ij xi_ij xi_ij^T, the derivative of
/// W_s through H_i vanishes: sum_j beta_ij z_ij (x) xi_ij = cv_i (H_i K_i - H_i K_i) = 0 for
/// every u. What is left splits into a graph Laplacian and a pointwise tensor:
///   S u = -lap(u) - G^T(T),   lap_l = sum_j c_lj (u_j - u_l),   T_i = cv_i H_i K_i,
/// with c_lj = cv_l wv_lj + cv_j wv_jl (docs/theory.md). lap comes out of the gradient pass
/// (one scalar per bond, held here and handed to NonlocalOperator::apply_with_laplacian) and
/// -T joins the V . P of the transposed product, so S costs one value and one multiply-add
/// per bond instead of S0's two-horizon pattern (about 75 bytes per bond in 3-D) or the
/// matrix-free bond passes. It needs symmetric families (j in H_i exactly when i in H_j: a
/// constant horizon radius), so that lap is a gather over the family rows; `make` tells.
class FusedStabilization {
 public:
  /// c_i = modulus / tr K_i from G's shape tensors (modulus = C_hg 2 mu). Returns nothing
  /// when G's graph is not symmetric. G must outlive this object.
  static std::optional<FusedStabilization> make(const PointCloud& cloud, const NonlocalOperator& G, double modulus);

  /// H = grad u (N x d x d) and lap (N x d) in one pass over the bonds.
  void gradient_and_laplacian(const double* u, double* H, double* lap) const;
  /// T[i] = cv_i H_i K_i for every particle (H and T: N x d x d).
  void tensor_terms(const double* H, double* T) const;
  /// After G.refresh_rows(rows): their cv_i K_i, and c of their bonds and of the reverse bonds.
  void refresh_rows(const std::vector<ParticleId>& rows);

  std::size_t memory_bytes() const {
    return (cvK_.size() + cv_.size() + volume_.size() + c_.size()) * sizeof(double) + c32_.size() * sizeof(float);
  }

 private:
  FusedStabilization(const PointCloud& cloud, const NonlocalOperator& G, double modulus);
  void refresh_particle(std::size_t i);
  void refresh_bond(Offset k, std::size_t l, std::size_t j);
  int dim_;
  double modulus_;
  const NonlocalOperator* G_;
  std::vector<double> cvK_;  // cv_i K_i, d x d per particle
  std::vector<double> cv_, volume_;
  std::vector<double> c_;    // c_lj per bond (row order), in G's weight precision
  std::vector<float> c32_;
};

}  // namespace perinom

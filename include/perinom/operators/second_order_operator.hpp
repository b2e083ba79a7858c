#pragma once
/// @file The assembled second-order nonlocal operators: gradient and Hessian from one
/// quadratic fit per family (THEORY sec. 6, seed 002 sec. 2).
#include <cstddef>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/families.hpp"
#include "perinom/operators/bond_weights.hpp"

namespace perinom {

/// What to assemble. The Hessian weights cost d(d+1)/2 doubles per bond in each orientation
/// (6 in 3-D, twice the gradient's 3): a scene that only needs the second-order gradient
/// (correspondence elasticity with operator_order 2) skips them.
struct SecondOrderOptions {
  bool hessian = true;  ///< assemble the Hessian weights h_ij
};

/// The second-order fit of THEORY sec. 6. With p_ij the basis of xi_ij = x_j - x_i,
///   2-D: (x, y, x^2/2, xy, y^2/2),  3-D: (x, y, z, x^2/2, xy, xz, y^2/2, yz, z^2/2),
/// K_i = (sum_j w_ij V_j p_ij p_ij^T)^-1 and K_i p_ij w_ij V_j = (g_ij ; h_ij):
/// d gradient weights and m = d(d+1)/2 Hessian weights per bond. Then
///   (grad f)_i = sum_j (f_j - f_i) g_ij,   (Hess f)_i = sum_j (f_j - f_i) h_ij,
/// exact for quadratic fields at every particle whose family determines the fit.
///
/// The m Hessian components are the distinct ones, in the order of the basis:
/// 2-D (xx, xy, yy); 3-D (xx, xy, xz, yy, yz, zz) (the basis' halves make them the second
/// derivatives themselves, not half of them).
///
/// Storage is that of GradientOperator, with one pattern for both operators: one column index
/// per bond in family (row) order and in dual-support order, and for each operator its
/// weights in both orders plus the diagonal -sum_j. So the four products are gathers, each
/// row summed in a fixed order by one thread (deterministic for any thread count).
class SecondOrderOperator {
 public:
  SecondOrderOperator() = default;
  /// Assembles the weights from the families and w_ij V_j (weights.wv). Throws InputError
  /// naming the first particle whose K_i is singular (the family does not determine a
  /// quadratic: fewer than 5 (2-D) or 9 (3-D) neighbours, or all on one conic).
  SecondOrderOperator(const PointCloud& cloud, const Families& families, const BondWeights& weights,
                      SecondOrderOptions options = {});

  int dim() const { return dim_; }
  /// m = d(d+1)/2: the Hessian components per particle and field component.
  int hessian_terms() const { return dim_ * (dim_ + 1) / 2; }
  bool has_hessian() const { return !hess_.diag.empty(); }
  std::size_t rows() const { return offsets_.size() - 1; }
  std::size_t bonds() const { return cols_.size(); }

  /// out = grad f: f holds N x nc values (point-major), out N x nc x d,
  /// out[(i*nc + c)*d + b] = sum_j (f_j[c] - f_i[c]) g_ij[b]. nc = 1, 2 or 3.
  void gradient(const double* f, int nc, double* out) const;
  /// out = Hess f: out holds N x nc x m, out[(i*nc + c)*m + s] = sum_j (f_j[c] - f_i[c]) h_ij[s].
  /// Throws std::logic_error when the Hessian was not assembled.
  void hessian(const double* f, int nc, double* out) const;

  /// The transposed gradient product, over the dual-support: q holds N x nc x d values,
  /// out[i*nc + c] = sum_b (G_b^T q[:, c, b])_i
  ///               = sum_{m in H'_i} g_mi . q_m[c] - (sum_{j in H_i} g_ij) . q_i[c].
  /// With `rows`, only those rows of out are written.
  void gradient_transpose(const double* q, int nc, double* out,
                          const std::vector<ParticleId>* rows = nullptr) const;
  /// The transposed Hessian product, likewise with h and q holding N x nc x m values. It is the
  /// adjoint for the plain dot product of the m stored components: an energy that counts the
  /// off-diagonal terms twice (M : kappa) passes them doubled in q.
  void hessian_transpose(const double* q, int nc, double* out,
                         const std::vector<ParticleId>* rows = nullptr) const;

  /// Bytes held by the operator (pattern, both orientations, both operators).
  std::size_t memory_bytes() const;

  // Raw access, for tangents and stabilizations built from the same weights.
  const std::vector<Offset>& offsets() const { return offsets_; }
  const std::vector<ParticleId>& cols() const { return cols_; }
  const std::vector<Offset>& dual_offsets() const { return t_offsets_; }
  const std::vector<ParticleId>& dual_cols() const { return t_cols_; }
  /// g_ij for bond k (d values) and h_ij (m values; only with the Hessian).
  const double* gradient_weight(Offset k) const { return grad_.w.data() + k * grad_.m; }
  const double* hessian_weight(Offset k) const { return hess_.w.data() + k * hess_.m; }
  /// -sum_j g_ij (d values) and -sum_j h_ij (m values) of row i.
  const double* gradient_diagonal(std::size_t i) const { return grad_.diag.data() + i * grad_.m; }
  const double* hessian_diagonal(std::size_t i) const { return hess_.diag.data() + i * hess_.m; }

 private:
  /// One operator's weights on the shared pattern: m values per bond in row order (w) and in
  /// dual-support order (t_w), and the diagonal (m values per particle).
  struct Block {
    int m = 0;
    std::vector<double> w, t_w, diag;
    std::size_t bytes() const { return (w.size() + t_w.size() + diag.size()) * sizeof(double); }
  };
  void apply(const Block& b, const double* f, int nc, double* out) const;
  void transpose(const Block& b, const double* q, int nc, double* out,
                 const std::vector<ParticleId>* rows) const;

  int dim_ = 0;
  std::vector<Offset> offsets_{0};
  std::vector<ParticleId> cols_;
  std::vector<Offset> t_offsets_{0};
  std::vector<ParticleId> t_cols_;
  Block grad_, hess_;
};

}  // namespace perinom

#pragma once
/// @file The assembled first-order nonlocal gradient G and its transpose (THEORY sec. 2-3).
#include <array>
#include <cstddef>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/families.hpp"
#include "perinom/operators/bond_weights.hpp"

namespace perinom {

/// How the bond weights g_ij are stored. float32 stores 16 instead of 28 bytes per bond and
/// product in 3-D, at the price of rounding the weights to 7 digits: the gradient of a
/// linear field is then exact to about 2e-8 (measured in the tests) instead of 1e-13 (the
/// diagonal is summed from the rounded weights, so constants stay exact). Arithmetic is
/// double either way.
enum class WeightPrecision { float64, float32 };

/// G_b (b = 1..d), N x N: (G_b)_ij = g_ij[b] for j in H_i, (G_b)_ii = -sum_j g_ij[b],
/// with g_ij = w_ij V_j K_i^-1 xi_ij. Stored block-sparse: one column index and d values
/// per bond, plus the diagonal; the transpose is stored the same way (rows = dual-support),
/// so both products are gathers and threads never write to the same row. Both products
/// are deterministic: each row is summed in a fixed order by one thread.
class GradientOperator {
 public:
  GradientOperator() = default;
  /// Assembles G from the families and their bond weights.
  GradientOperator(const PointCloud& cloud, const Families& families, const BondWeights& weights,
                   WeightPrecision precision = WeightPrecision::float64);
  /// G from given weights: g[k*dim + b] for bond k of the families (row order), e.g. the
  /// gradient weights of the second-order fit (SecondOrderOperator::gradient_weight); the
  /// diagonal, the transpose and the products are those of the first-order G.
  GradientOperator(const Families& families, int dim, std::vector<double> g,
                   WeightPrecision precision = WeightPrecision::float64);

  int dim() const { return dim_; }
  std::size_t rows() const { return offsets_.size() - 1; }
  std::size_t bonds() const { return cols_.size(); }
  WeightPrecision precision() const { return precision_; }

  /// out = grad f: f holds N x nc values (point-major); out holds N x nc x d,
  /// out[(i*nc + c)*d + b] = sum_j (f_j[c] - f_i[c]) g_ij[b].
  void apply(const double* f, int nc, double* out) const;

  /// out[i*nc + c] = sum_b (G_b^T q[:, c, b])_i, q holding N x nc x d values.
  /// For nc = d and q = V.P this is the weak-form internal force (THEORY sec. 3).
  /// With `rows`, only those rows of out are written.
  void apply_transpose(const double* q, int nc, double* out,
                       const std::vector<ParticleId>* rows = nullptr) const;

  /// The nonlocal divergence of a tensor field: out[i*nc + c] = sum_b (G_b q[:, c, b])_i
  /// = sum_j sum_b (q_j - q_i)[c][b] g_ij[b], for q holding N x nc x d values (the strong
  /// form of THEORY sec. 5 for q = P). With `rows`, only those rows of out are written.
  void divergence(const double* q, int nc, double* out,
                  const std::vector<ParticleId>* rows = nullptr) const;

  /// Attaches one scalar c_ij per bond (row order, stored in the operator's precision), for
  /// apply_with_laplacian. Replaces any earlier ones.
  void set_bond_scalars(const std::vector<double>& c);
  bool has_bond_scalars() const { return !c_.empty() || !c32_.empty(); }
  /// apply(f, d, out) and, in the same pass over the bonds, lap[i*d + a] =
  /// sum_j c_ij (f_j - f_i)[a]: the graph Laplacian weighted by the bond scalars (one
  /// more multiply-add and one more stored value per bond). Needs set_bond_scalars.
  void apply_with_laplacian(const double* f, double* out, double* lap) const;

  /// Bytes held by the operator (both orientations).
  std::size_t memory_bytes() const;

  // Raw access, for assembling tangents and the stabilization from the same weights.
  const std::vector<Offset>& offsets() const { return offsets_; }
  const std::vector<ParticleId>& cols() const { return cols_; }
  /// g_ij for bond k (d values; as stored, so rounded under float32).
  std::array<double, 3> weight(Offset k) const { return stored(w_, w32_, k); }
  const double* diagonal(std::size_t i) const { return diag_.data() + i * dim_; }
  const std::vector<Offset>& dual_offsets() const { return t_offsets_; }
  const std::vector<ParticleId>& dual_cols() const { return t_cols_; }
  /// g_mi for the k-th dual-support entry (m = dual_cols()[k]) of row i.
  std::array<double, 3> dual_weight(Offset k) const { return stored(t_w_, t_w32_, k); }

 private:
  std::array<double, 3> stored(const std::vector<double>& w64, const std::vector<float>& w32,
                               Offset k) const {
    std::array<double, 3> g{0.0, 0.0, 0.0};
    for (int b = 0; b < dim_; ++b) g[b] = w32.empty() ? w64[k * dim_ + b] : double(w32[k * dim_ + b]);
    return g;
  }

  /// From w_ (rounded to the precision already): the diagonal, the transpose, the float32 copies.
  void finish(const Families& families);

  int dim_ = 0;
  WeightPrecision precision_ = WeightPrecision::float64;
  std::vector<Offset> offsets_{0};
  std::vector<ParticleId> cols_;
  std::vector<double> w_, diag_;
  std::vector<Offset> t_offsets_{0};
  std::vector<ParticleId> t_cols_;
  std::vector<double> t_w_;
  std::vector<float> w32_, t_w32_;  // the weights, when stored in single precision
  std::vector<double> c_;           // bond scalars (set_bond_scalars), double precision
  std::vector<float> c32_;          // or single
};

}  // namespace perinom

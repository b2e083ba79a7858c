#pragma once
/// @file The nonlocal operator: the first-order gradient G, or the second-order gradient and
/// Hessian from one quadratic fit, assembled on a bond graph (THEORY sec. 2, 3 and 6).
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/bond_graph.hpp"
#include "perinom/neighbors/families.hpp"
#include "perinom/operators/bond_weights.hpp"

namespace perinom {

/// How the bond weights are stored. float32 stores 16 instead of 28 bytes per bond and
/// product in 3-D, at the price of rounding the weights to 7 digits: the gradient of a
/// linear field is then exact to about 2e-8 (measured in the tests) instead of 1e-13 (the
/// diagonal is summed from the rounded weights, so constants stay exact). Arithmetic is
/// double either way.
enum class WeightPrecision { float64, float32 };

/// Which weights a product uses: the gradient's d, or the Hessian's d(d+1)/2 per bond.
enum class Derivative { gradient, hessian };

/// What to assemble.
struct OperatorOptions {
  /// 1: the first-order fit, g_ij = w_ij V_j K_i^-1 xi_ij (THEORY sec. 2).
  /// 2: the quadratic fit of THEORY sec. 6: its gradient weights, and its Hessian weights
  ///    when `hessian` is set (d(d+1)/2 more doubles per bond in each orientation).
  int order = 1;
  bool hessian = false;
  WeightPrecision precision = WeightPrecision::float64;  ///< order 1 only
  /// Rows from this one on are not fitted: their weights stay zero (their shape tensors are
  /// still formed). A distributed rank's far ghosts (neighbors/local_part.hpp), whose families
  /// the local part truncates and whose rows nothing reads, only lend their values.
  std::size_t fitted_rows = SIZE_MAX;
};

/// Where a field's values sit: component c of particle i at f[i * stride + c], c <
/// components; stride 0 means components (point-major). An interleaved multi-field vector
/// (e.g. d displacements then a phase field per particle) is read or written in place.
struct FieldLayout {
  int components = 1;
  int stride = 0;
};

/// D (N x N per weight): D[i][j] = a_ij for j in H_i, D[i][i] = -sum_j a_ij, with a_ij the
/// M weights of bond (i, j): M = d for a gradient, m = d(d+1)/2 for the Hessian. Then
///   (D f)_i = sum_j (f_j - f_i) a_ij,
/// exact for linear (order 1) or quadratic (order 2) fields at every particle whose family
/// determines the fit. The Hessian's m components are the distinct ones, in the order
/// 2-D (xx, xy, yy), 3-D (xx, xy, xz, yy, yz, zz) (second derivatives, not halves).
///
/// Storage: the pattern is the bond graph's (shared, never copied); per bond M weights in
/// row order and in dual-support order, and the diagonal. So every product is a gather, each
/// row summed in a fixed order by one thread: deterministic for any thread count.
///
/// Broken bonds: refresh_rows recomputes rows from the live bonds (a dead bond keeps its slot
/// with weight zero). A particle whose live family no longer determines the fit is detached:
/// its row and its transposed entries are zero, so it carries no gradient and no stress.
class NonlocalOperator {
 public:
  /// Order 1: a family is detached below this quality q = det K / (tr K / d)^d of its shape
  /// tensor (scale-free; 1 for an isotropic family, 0 for one that spans a line or a plane).
  static constexpr double detach_quality = 1e-8;
  /// Order 2: the fit is detached when the ratio of the extreme eigenvalues of its moment
  /// matrix (in the basis of xi / delta_i) falls to this.
  static constexpr double detach_ratio = 1e-10;
  /// Order 1, after breaks: a family is also detached when the smallest eigenvalue of its
  /// shape tensor falls below this share of its value at assembly. The row's stiffness grows
  /// as that eigenvalue falls (G_i = K_i^-1 ...), so a particle hanging on a few bonds would
  /// need a time step far below the one the run started with; this bounds the growth to
  /// about 1 / detach_share (measured on a bar that breaks through: docs/verification/bar.md).
  static constexpr double detach_share = 0.25;

  NonlocalOperator() = default;
  /// Assembles the weights from the live bonds of `graph` and w_ij V_j (weights.wv). Throws
  /// InputError naming the first particle whose fit is singular.
  NonlocalOperator(const PointCloud& cloud, std::shared_ptr<const BondGraph> graph, const BondWeights& weights,
                   OperatorOptions options = {});
  /// The same on a graph of its own, built from `families`.
  NonlocalOperator(const PointCloud& cloud, const Families& families, const BondWeights& weights,
                   OperatorOptions options = {});
  /// A gradient from given weights: g[k*dim + b] for bond k (row order), e.g. the consistent
  /// formulation's G~. Not from a local fit, so refresh_rows cannot reproduce it and throws.
  NonlocalOperator(std::shared_ptr<const BondGraph> graph, int dim, std::vector<double> g,
                   WeightPrecision precision = WeightPrecision::float64);
  NonlocalOperator(const Families& families, int dim, std::vector<double> g,
                   WeightPrecision precision = WeightPrecision::float64);

  int dim() const { return dim_; }
  int order() const { return order_; }
  /// The rows the constructor fitted (OperatorOptions::fitted_rows; all by default).
  std::size_t fitted_rows() const { return std::min(fitted_rows_, rows()); }
  /// m = d(d+1)/2: the Hessian components per particle and field component.
  int hessian_terms() const { return dim_ * (dim_ + 1) / 2; }
  bool has_hessian() const { return hess_.m > 0; }
  /// M of a derivative: d for the gradient, hessian_terms() for the Hessian.
  int weights_per_bond(Derivative which) const { return block(which).m; }
  std::size_t rows() const { return graph_ ? graph_->rows() : 0; }
  /// A distributed rank's local operator evaluates only its first rows (owned, then the ghosts
  /// it reads, neighbors/local_part.hpp): apply (and apply_with_laplacian) writes the first
  /// `gradient_rows`, apply_transpose and divergence without a subset the first
  /// `transpose_rows`; the other rows of their outputs are left as they were. All rows by default.
  void limit_rows(std::size_t gradient_rows, std::size_t transpose_rows) {
    gradient_rows_ = gradient_rows, transpose_rows_ = transpose_rows;
  }
  std::size_t gradient_rows() const { return std::min(gradient_rows_, rows()); }
  std::size_t transpose_rows() const { return std::min(transpose_rows_, rows()); }
  std::size_t bonds() const { return graph_ ? graph_->bonds() : 0; }
  WeightPrecision precision() const { return precision_; }
  const BondGraph& graph() const { return *graph_; }
  const std::shared_ptr<const BondGraph>& shared_graph() const { return graph_; }

  /// out = D f: f holds nc components per particle (layout), out N x nc x M,
  /// out[(i*nc + c)*M + b] = sum_j (f_j[c] - f_i[c]) a_ij[b].
  void apply(const double* f, int nc, double* out, Derivative which = Derivative::gradient) const {
    apply(f, FieldLayout{nc, nc}, out, which);
  }
  void apply(const double* f, FieldLayout layout, double* out, Derivative which = Derivative::gradient) const;

  /// out[i*nc + c] = sum_b (D_b^T q[:, c, b])_i
  ///               = sum_{m in H'_i} a_mi . q_m[c] - (sum_{j in H_i} a_ij) . q_i[c],
  /// q holding N x nc x M values. For the gradient, nc = d and q = V.P this is the weak-form
  /// internal force (THEORY sec. 3). For the Hessian it is the adjoint for the plain dot
  /// product of the m stored components (an energy that counts the off-diagonal terms twice
  /// passes them doubled in q). With `rows`, only those rows of out are written.
  void apply_transpose(const double* q, int nc, double* out, const std::vector<ParticleId>* rows = nullptr,
                       Derivative which = Derivative::gradient) const {
    apply_transpose(q, FieldLayout{nc, nc}, out, rows, which);
  }
  /// The same, out written at out[i*stride + c] (layout.components = nc).
  void apply_transpose(const double* q, FieldLayout layout, double* out, const std::vector<ParticleId>* rows = nullptr,
                       Derivative which = Derivative::gradient) const;

  /// The nonlocal divergence of a tensor field: out[i*nc + c] = sum_j sum_b (q_j - q_i)[c][b]
  /// g_ij[b], for q holding N x nc x d values (the strong form of THEORY sec. 5 for q = P).
  /// With `rows`, only those rows of out are written.
  void divergence(const double* q, int nc, double* out, const std::vector<ParticleId>* rows = nullptr) const {
    divergence(q, FieldLayout{nc, nc}, out, rows);
  }
  void divergence(const double* q, FieldLayout layout, double* out, const std::vector<ParticleId>* rows = nullptr) const;

  /// The gradient (f of d components) and, in the same pass over the bonds, lap[i*d + a] =
  /// sum_j c_ij (f_j - f_i)[a]: the graph Laplacian of bond scalars c (one per bond, row
  /// order) that the caller owns (the fused stabilization). c holds doubles, or floats
  /// under float32 weights (as the weights are).
  void apply_with_laplacian(const double* f, const double* c, double* out, double* lap) const;
  void apply_with_laplacian(const double* f, const float* c, double* out, double* lap) const;

  /// Row i of D: f(i, a_ii) for the diagonal, then f(j, a_ij) for each live bond in column
  /// order (a: M doubles, as stored: rounded under float32).
  template <class F>
  void visit_row(std::size_t i, F&& f, Derivative which = Derivative::gradient) const {
    const Block& b = block(which);
    double a[6];
    f(static_cast<ParticleId>(i), b.diag.data() + i * b.m);
    for (Offset k = graph_->begin(i); k < graph_->end(i); ++k)
      if (graph_->alive(k)) f(graph_->col(k), b.stored(k, a));
  }
  /// Column i of D (row i of D^T): f(i, a_ii), then f(m, a_mi) for each live bond (m, i),
  /// m in the dual support of i.
  template <class F>
  void visit_column(std::size_t i, F&& f, Derivative which = Derivative::gradient) const {
    const Block& b = block(which);
    double a[6];
    f(static_cast<ParticleId>(i), b.diag.data() + i * b.m);
    for (Offset t = graph_->dual_begin(i); t < graph_->dual_end(i); ++t)
      if (graph_->dual_alive(t)) f(graph_->dual_col(t), b.stored_dual(t, a));
  }

  /// Recomputes rows from the live bonds of the graph: their weights in both orientations
  /// and their diagonal, in O(the rows' bonds). Rows whose family no longer determines the
  /// fit are detached (see the class). Throws std::logic_error for given weights (the
  /// consistent G~ comes from a global correction: a local refresh is not implemented).
  void refresh_rows(const std::vector<ParticleId>& rows);
  /// True when refresh_rows can recompute this operator (its weights come from a local fit).
  bool refreshable() const { return !x_.empty(); }
  /// The detached particles, sorted.
  const std::vector<ParticleId>& detached() const { return detached_; }
  bool is_detached(std::size_t i) const { return !attached_.empty() && !attached_[i]; }
  /// The first-order shape tensor K_i = sum_j w_ij V_j xi_ij (x) xi_ij of the live family
  /// (d x d, row-major; zero when detached). Only for an operator from a fit (refreshable).
  const double* shape(std::size_t i) const { return K_.data() + i * dim_ * dim_; }

  /// Bytes held by the operator (both orientations; the shared graph not included).
  std::size_t memory_bytes() const;

 private:
  friend struct OperatorAccess;  // lib/operators/operator_access.hpp
  /// One derivative's weights: m per bond in row order (w) and dual order (t_w), in double or
  /// float, and the diagonal -sum_j (always double).
  struct Block {
    int m = 0;
    std::vector<double> w, t_w, diag;
    std::vector<float> w32, t_w32;
    const double* stored(Offset k, double* a) const {
      if (w32.empty()) return w.data() + k * m;
      for (int r = 0; r < m; ++r) a[r] = double(w32[k * m + r]);
      return a;
    }
    const double* stored_dual(Offset t, double* a) const {
      if (t_w32.empty()) return t_w.data() + t * m;
      for (int r = 0; r < m; ++r) a[r] = double(t_w32[t * m + r]);
      return a;
    }
    double get(Offset k, int r) const { return w32.empty() ? w[k * m + r] : double(w32[k * m + r]); }
    double get_dual(Offset t, int r) const { return t_w32.empty() ? t_w[t * m + r] : double(t_w32[t * m + r]); }
    void set(Offset k, Offset t, int r, double v) {
      if (w32.empty()) w[k * m + r] = t_w[t * m + r] = v;
      else w32[k * m + r] = t_w32[t * m + r] = float(v);
    }
    std::size_t bytes() const {
      return (w.size() + t_w.size() + diag.size()) * sizeof(double) + (w32.size() + t_w32.size()) * sizeof(float);
    }
  };
  const Block& block(Derivative which) const { return which == Derivative::hessian ? hess_ : grad_; }
  void allocate();
  /// Row i from the live bonds (weights in both orientations, diagonal); false when the live
  /// family does not determine the fit (the row is then left for detach_row).
  bool fit_row(std::size_t i);
  /// Row i's shape tensor K into K_ (and its inverse into Kinv when given); false when the
  /// family does not span the space.
  bool form_shape_tensor(std::size_t i, double* Kinv = nullptr);
  bool fit_first_order(std::size_t i, const double* Kinv);  // nonlocal_products.cpp
  bool fit_second_order(std::size_t i);
  void finish_row(std::size_t i);
  void detach_row(std::size_t i);

  std::shared_ptr<const BondGraph> graph_;
  std::size_t gradient_rows_ = SIZE_MAX, transpose_rows_ = SIZE_MAX;  // limit_rows
  std::size_t fitted_rows_ = SIZE_MAX;                                  // OperatorOptions::fitted_rows
  int dim_ = 0, order_ = 1;
  WeightPrecision precision_ = WeightPrecision::float64;
  std::vector<double> x_, wv_;  // positions and w_ij V_j (row order): the inputs of a refresh
  std::vector<double> K_;       // K_i of the live family
  std::vector<double> kmin0_;   // the smallest eigenvalue of K_i at assembly (order 1)
  std::vector<std::uint8_t> attached_;
  std::vector<ParticleId> detached_;
  Block grad_, hess_;
};

}  // namespace perinom

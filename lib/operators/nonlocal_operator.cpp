// The assembly and refresh of NonlocalOperator (its products are in nonlocal_products.cpp,
// compiled for this machine's processor; this file uses Eigen and is not: lib/CMakeLists.txt).
#include "perinom/operators/nonlocal_operator.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "perinom/core/error.hpp"
#include "perinom/operators/singular_family.hpp"
#include "shape_tensor.hpp"

namespace perinom {
namespace {

// The smallest eigenvalue of a symmetric d x d shape tensor (row-major).
double smallest_eigenvalue(int d, const double* K) {
  if (d == 2) return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(Eigen::Map<const Eigen::Matrix2d>(K)).eigenvalues()[0];
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Eigen::Map<const Eigen::Matrix3d>(K)).eigenvalues()[0];
}

// The basis of THEORY sec. 6 at a bond: d linear terms, then the d(d+1)/2 quadratic ones in
// the order (xx/2, xy, xz, yy/2, yz, zz/2).
void basis(int d, const double* xi, double* p) {
  for (int a = 0; a < d; ++a) p[a] = xi[a];
  int r = d;
  for (int a = 0; a < d; ++a)
    for (int b = a; b < d; ++b) p[r++] = a == b ? 0.5 * xi[a] * xi[a] : xi[a] * xi[b];
}

[[noreturn]] void report_singular(int d, const double* x, const BondGraph& graph, int order, std::size_t i) {
  throw SingularFamily(d, x, static_cast<ParticleId>(i), static_cast<long>(graph.end(i) - graph.begin(i)), order);
}

std::shared_ptr<const BondGraph> graph_of(const Families& families) {
  return std::make_shared<const BondGraph>(families);
}

}  // namespace

NonlocalOperator::NonlocalOperator(const PointCloud& cloud, std::shared_ptr<const BondGraph> graph,
                                   const BondWeights& weights, OperatorOptions options)
    : graph_(std::move(graph)), dim_(cloud.dim), order_(options.order), precision_(options.precision),
      x_(cloud.x), wv_(weights.wv) {
  fitted_rows_ = options.fitted_rows;
  if (order_ != 1 && order_ != 2)
    throw std::invalid_argument("NonlocalOperator: order must be 1 or 2, not " + std::to_string(order_));
  if (graph_->rows() != cloud.size() || wv_.size() != graph_->bonds())
    throw std::invalid_argument("NonlocalOperator: " + std::to_string(cloud.size()) + " particles and " +
                                std::to_string(wv_.size()) + " bond weights for a graph of " +
                                std::to_string(graph_->rows()) + " rows and " + std::to_string(graph_->bonds()) +
                                " bonds");
  grad_.m = dim_;
  hess_.m = order_ == 2 && options.hessian ? hessian_terms() : 0;
  allocate();
  const std::size_t n = rows(), fitted = fitted_rows();
  long singular = -1;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i)
    if (i >= fitted) {
      form_shape_tensor(i);
    } else if (!fit_row(i)) {
#pragma omp critical
      if (singular < 0 || static_cast<long>(i) < singular) singular = static_cast<long>(i);
    }
  if (singular >= 0) report_singular(dim_, x_.data(), *graph_, order_, static_cast<std::size_t>(singular));
}

NonlocalOperator::NonlocalOperator(const PointCloud& cloud, const Families& families, const BondWeights& weights,
                                   OperatorOptions options)
    : NonlocalOperator(cloud, graph_of(families), weights, options) {}

NonlocalOperator::NonlocalOperator(std::shared_ptr<const BondGraph> graph, int dim, std::vector<double> g,
                                   WeightPrecision precision)
    : graph_(std::move(graph)), dim_(dim), precision_(precision) {
  if (g.size() != bonds() * dim)
    throw std::invalid_argument("NonlocalOperator: " + std::to_string(g.size()) + " weights for " +
                                std::to_string(bonds()) + " bonds in " + std::to_string(dim) + "-D");
  grad_.m = dim;
  allocate();
  for (std::size_t i = 0; i < rows(); ++i) {
    for (Offset k = graph_->begin(i); k < graph_->end(i); ++k)
      for (int b = 0; b < dim; ++b) {
        const double v = g[k * dim + b];
        grad_.set(k, graph_->dual_entry(k), b, precision == WeightPrecision::float32 ? double(float(v)) : v);
      }
    finish_row(i);
  }
}

NonlocalOperator::NonlocalOperator(const Families& families, int dim, std::vector<double> g, WeightPrecision precision)
    : NonlocalOperator(graph_of(families), dim, std::move(g), precision) {}

void NonlocalOperator::allocate() {
  const std::size_t n = rows(), nb = bonds();
  for (Block* b : {&grad_, &hess_}) {
    if (b->m == 0) continue;
    if (precision_ == WeightPrecision::float32) {
      b->w32.assign(nb * b->m, 0.0f);
      b->t_w32.assign(nb * b->m, 0.0f);
    } else {
      b->w.assign(nb * b->m, 0.0);
      b->t_w.assign(nb * b->m, 0.0);
    }
    b->diag.assign(n * b->m, 0.0);
  }
  attached_.assign(n, 1);
  if (!x_.empty()) K_.assign(n * dim_ * dim_, 0.0);
  if (!x_.empty() && order_ == 1) kmin0_.assign(n, 0.0);
}

bool NonlocalOperator::form_shape_tensor(std::size_t i, double* Kinv) {
  double unused[9];
  return shape_tensor(dim_, x_.data(), i, graph_->begin(i), graph_->end(i), graph_->cols().data(), wv_.data(),
                      graph_->alive_mask().data(), K_.data() + i * dim_ * dim_, Kinv ? Kinv : unused);
}

bool NonlocalOperator::fit_row(std::size_t i) {
  const int d = dim_;
  double Kinv[9];
  double* K = K_.data() + i * d * d;
  const bool spans = form_shape_tensor(i, Kinv);
  if (order_ == 2) return fit_second_order(i);
  if (!spans || shape_quality(d, K) < detach_quality) return false;
  const double kmin = smallest_eigenvalue(d, K);
  if (kmin0_[i] == 0.0) kmin0_[i] = kmin;  // the first fit: at assembly
  else if (kmin < detach_share * kmin0_[i]) return false;
  return fit_first_order(i, Kinv);
}

bool NonlocalOperator::fit_second_order(std::size_t i) {
  const int d = dim_, nb = d + hessian_terms();
  const BondGraph& g = *graph_;
  std::vector<Offset> live;
  for (Offset k = g.begin(i); k < g.end(i); ++k)
    if (g.alive(k)) live.push_back(k);
  const Eigen::Index size = static_cast<Eigen::Index>(live.size());
  // K_i^-1 is formed in the basis of xi / s, s the family radius, so its entries are O(1) and
  // the ratio of its extreme eigenvalues measures the family's shape, not its units.
  const double s = g.families().support[i] > 0.0 ? g.families().support[i] : 1.0;
  Eigen::MatrixXd P(nb, size);  // one column p(xi / s) per live bond
  Eigen::VectorXd wv(size);
  for (Eigen::Index c = 0; c < size; ++c) {
    const std::size_t j = g.col(live[c]);
    double xi[3];
    for (int a = 0; a < d; ++a) xi[a] = (x_[j * d + a] - x_[i * d + a]) / s;
    basis(d, xi, P.col(c).data());
    wv[c] = wv_[live[c]];
  }
  const Eigen::MatrixXd moments = P * wv.asDiagonal() * P.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(moments);
  const auto lambda = eig.eigenvalues();
  if (!(lambda.maxCoeff() > 0.0) || lambda.minCoeff() <= detach_ratio * lambda.maxCoeff()) return false;
  const Eigen::MatrixXd& Q = eig.eigenvectors();
  // Rows: the fit's unknowns in the scaled basis; dividing by s (linear) and s^2 (quadratic)
  // gives K_i p_ij w_ij V_j in the units of xi.
  Eigen::MatrixXd W = Q * lambda.cwiseInverse().asDiagonal() * Q.transpose() * P * wv.asDiagonal();
  W.topRows(d) /= s;
  W.bottomRows(nb - d) /= s * s;
  const bool single = precision_ == WeightPrecision::float32;
  for (Block* b : {&grad_, &hess_}) {
    if (b->m == 0) continue;
    const int row0 = b == &grad_ ? 0 : d;
    for (Offset k = g.begin(i); k < g.end(i); ++k)
      for (int r = 0; r < b->m; ++r) b->set(k, g.dual_entry(k), r, 0.0);
    for (Eigen::Index c = 0; c < size; ++c)
      for (int r = 0; r < b->m; ++r) {
        const double v = W(row0 + r, c);
        b->set(live[c], g.dual_entry(live[c]), r, single ? double(float(v)) : v);
      }
  }
  finish_row(i);
  return true;
}

void NonlocalOperator::finish_row(std::size_t i) {
  // The diagonal sums the weights as stored, so D of a constant is zero under float32 too.
  for (Block* b : {&grad_, &hess_}) {
    if (b->m == 0) continue;
    double* diag = b->diag.data() + i * b->m;
    for (int r = 0; r < b->m; ++r) diag[r] = 0.0;
    for (Offset k = graph_->begin(i); k < graph_->end(i); ++k)
      for (int r = 0; r < b->m; ++r) diag[r] -= b->get(k, r);
  }
}

void NonlocalOperator::detach_row(std::size_t i) {
  for (Block* b : {&grad_, &hess_}) {
    if (b->m == 0) continue;
    for (Offset k = graph_->begin(i); k < graph_->end(i); ++k)
      for (int r = 0; r < b->m; ++r) b->set(k, graph_->dual_entry(k), r, 0.0);
    for (int r = 0; r < b->m; ++r) b->diag[i * b->m + r] = 0.0;
  }
  if (!K_.empty()) std::fill(K_.begin() + i * dim_ * dim_, K_.begin() + (i + 1) * dim_ * dim_, 0.0);
  attached_[i] = 0;
}

void NonlocalOperator::refresh_rows(const std::vector<ParticleId>& rows_in) {
  if (!refreshable())
    throw std::logic_error(
        "NonlocalOperator::refresh_rows: not implemented for given weights (the consistent formulation's "
        "G~ comes from a global correction that a local refresh cannot reproduce)");
  std::vector<ParticleId> rows = rows_in;
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  // Each row writes its own bonds in both orientations (distinct dual entries): no races.
#pragma omp parallel for schedule(dynamic, 16) if (rows.size() > 64)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::size_t i = rows[r];
    if (fit_row(i)) attached_[i] = 1;
    else detach_row(i);
  }
  detached_.clear();
  for (std::size_t i = 0; i < attached_.size(); ++i)
    if (!attached_[i]) detached_.push_back(static_cast<ParticleId>(i));
}

std::size_t NonlocalOperator::memory_bytes() const {
  return grad_.bytes() + hess_.bytes() + (x_.size() + wv_.size() + K_.size() + kmin0_.size()) * sizeof(double) +
         attached_.size() + detached_.size() * sizeof(ParticleId);
}

}  // namespace perinom

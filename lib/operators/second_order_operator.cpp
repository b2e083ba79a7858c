#include "perinom/operators/second_order_operator.hpp"

#include <Eigen/Dense>
#include <sstream>
#include <string>

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

// K_i^-1 is formed in the basis of xi / s, s the family radius, so its entries are O(1) and
// this ratio of its extreme eigenvalues measures the family's shape, not its units.
constexpr double singular_ratio = 1e-10;

// The basis of THEORY sec. 6 at a bond: d linear terms, then the d(d+1)/2 quadratic ones in
// the order (xx/2, xy, xz, yy/2, yz, zz/2).
void basis(int d, const double* xi, double* p) {
  for (int a = 0; a < d; ++a) p[a] = xi[a];
  int r = d;
  for (int a = 0; a < d; ++a)
    for (int b = a; b < d; ++b) p[r++] = a == b ? 0.5 * xi[a] * xi[a] : xi[a] * xi[b];
}

[[noreturn]] void report_singular(const PointCloud& cloud, const Families& families, long i) {
  const int d = cloud.dim;
  std::ostringstream msg;
  msg << "particle " << i << " at (";
  for (int a = 0; a < d; ++a) msg << (a ? ", " : "") << cloud.x[i * d + a];
  msg << "): the second-order K is singular; its family of " << families.end(i) - families.begin(i)
      << " neighbours does not determine a quadratic in R^" << d << " (that takes at least "
      << d + d * (d + 1) / 2
      << " neighbours, not all on one conic or quadric: e.g. three distinct layers along each "
         "axis; increase discretization.horizon.ratio or discretization.horizon.neighbors)";
  throw InputError(msg.str());
}

}  // namespace

SecondOrderOperator::SecondOrderOperator(const PointCloud& cloud, const Families& families,
                                         const BondWeights& bw, SecondOrderOptions options)
    : dim_(cloud.dim), offsets_(families.offsets), cols_(families.neighbors) {
  const int d = dim_, nb = d + hessian_terms();
  const std::size_t n = rows();
  grad_.m = d;
  grad_.w.resize(bonds() * d);
  grad_.diag.assign(n * d, 0.0);
  if (options.hessian) {
    hess_.m = hessian_terms();
    hess_.w.resize(bonds() * hess_.m);
    hess_.diag.assign(n * hess_.m, 0.0);
  }
  long singular = -1;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    const Offset first = offsets_[i];
    const Eigen::Index size = offsets_[i + 1] - first;
    const double s = families.support[i] > 0.0 ? families.support[i] : 1.0;
    Eigen::MatrixXd P(nb, size);  // one column p(xi / s) per bond
    for (Eigen::Index k = 0; k < size; ++k) {
      const std::size_t j = cols_[first + k];
      double xi[3];
      for (int a = 0; a < d; ++a) xi[a] = (cloud.x[j * d + a] - cloud.x[i * d + a]) / s;
      basis(d, xi, P.col(k).data());
    }
    const Eigen::Map<const Eigen::VectorXd> wv(bw.wv.data() + first, size);
    const Eigen::MatrixXd moments = P * wv.asDiagonal() * P.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(moments);
    const auto lambda = eig.eigenvalues();
    if (!(lambda.maxCoeff() > 0.0) || lambda.minCoeff() <= singular_ratio * lambda.maxCoeff()) {
#pragma omp critical
      if (singular < 0 || static_cast<long>(i) < singular) singular = static_cast<long>(i);
      continue;
    }
    const Eigen::MatrixXd& Q = eig.eigenvectors();
    // Rows: the fit's unknowns in the scaled basis; dividing by s (linear) and s^2 (quadratic)
    // gives K_i p_ij w_ij V_j in the units of xi.
    Eigen::MatrixXd W = Q * lambda.cwiseInverse().asDiagonal() * Q.transpose() * P * wv.asDiagonal();
    W.topRows(d) /= s;
    W.bottomRows(nb - d) /= s * s;
    for (Block* b : {&grad_, &hess_}) {
      if (b->m == 0) continue;
      const int row0 = b == &grad_ ? 0 : d;
      for (Eigen::Index k = 0; k < size; ++k)
        for (int r = 0; r < b->m; ++r) {
          b->w[(first + k) * b->m + r] = W(row0 + r, k);
          b->diag[i * b->m + r] -= W(row0 + r, k);
        }
    }
  }
  if (singular >= 0) report_singular(cloud, families, singular);

  DualSupport dual = dual_support(families);
  t_offsets_ = std::move(dual.offsets);
  t_cols_ = std::move(dual.neighbors);
  for (Block* b : {&grad_, &hess_}) {
    b->t_w.resize(b->w.size());
    for (std::size_t k = 0; k < dual.bond.size() && b->m > 0; ++k)
      for (int r = 0; r < b->m; ++r) b->t_w[k * b->m + r] = b->w[dual.bond[k] * b->m + r];
  }
}

std::size_t SecondOrderOperator::memory_bytes() const {
  return (offsets_.size() + t_offsets_.size()) * sizeof(Offset) +
         (cols_.size() + t_cols_.size()) * sizeof(ParticleId) + grad_.bytes() + hess_.bytes();
}

}  // namespace perinom

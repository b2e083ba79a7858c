#include "perinom/operators/second_order_stabilization.hpp"

#include "perinom/core/parallel.hpp"

namespace perinom {

SecondOrderStabilization::SecondOrderStabilization(const PointCloud& cloud, const BondWeights& weights,
                                                   const SecondOrderOperator& op, std::vector<double> cv)
    : dim_(cloud.dim), nb_(cloud.dim + op.hessian_terms()), op_(&op), x_(cloud.x), cv_(std::move(cv)),
      wv_(weights.wv), t_wv_(op.dual_cols().size()), b_(op.rows() * nb_, 0.0), r_(op.rows(), 0.0) {
  // The dual-support order of the bonds: position t of (i, l) in l's dual row is the k of
  // (i, l) in i's family row.
  std::vector<Offset> next(op.dual_offsets().begin(), op.dual_offsets().end() - 1);
  for (std::size_t i = 0; i < op.rows(); ++i)
    for (Offset k = op.offsets()[i]; k < op.offsets()[i + 1]; ++k) t_wv_[next[op.cols()[k]]++] = wv_[k];
  double p[9];
  for (std::size_t i = 0; i < op.rows(); ++i)
    for (Offset k = op.offsets()[i]; k < op.offsets()[i + 1]; ++k) {
      basis(i, op.cols()[k], p);
      for (int s = 0; s < nb_; ++s) b_[i * nb_ + s] += wv_[k] * p[s];
    }
}

void SecondOrderStabilization::basis(std::size_t i, std::size_t j, double* p) const {
  const int d = dim_;
  double xi[3];
  for (int a = 0; a < d; ++a) xi[a] = x_[j * d + a] - x_[i * d + a];
  for (int a = 0; a < d; ++a) p[a] = xi[a];
  int r = d;
  for (int a = 0; a < d; ++a)
    for (int b = a; b < d; ++b) p[r++] = a == b ? 0.5 * xi[a] * xi[a] : xi[a] * xi[b];
}

double SecondOrderStabilization::z(std::size_t i, std::size_t j, const double* f, const double* grad,
                                   const double* hess) const {
  double p[9];
  basis(i, j, p);
  const int d = dim_, m = nb_ - d;
  double s = f[j] - f[i];
  for (int a = 0; a < d; ++a) s -= p[a] * grad[i * d + a];
  for (int q = 0; q < m; ++q) s -= p[d + q] * hess[i * m + q];
  return s;
}

void SecondOrderStabilization::add_force(const double* f, const double* grad, const double* hess, double* out) {
  const std::size_t n = op_->rows();
  const Offset* off = op_->offsets().data();
  const ParticleId* col = op_->cols().data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double r = 0.0;
    if (cv_[i] > 0.0)
      for (Offset k = off[i]; k < off[i + 1]; ++k) r += wv_[k] * z(i, col[k], f, grad, hess);
    r_[i] = cv_[i] * r;
  }
  const Offset* t_off = op_->dual_offsets().data();
  const ParticleId* t_col = op_->dual_cols().data();
#pragma omp parallel for schedule(static)
  for (std::size_t l = 0; l < n; ++l) {
    double acc = -r_[l];
    for (Offset t = t_off[l]; t < t_off[l + 1]; ++t) {
      const std::size_t i = t_col[t];
      if (cv_[i] > 0.0) acc += cv_[i] * t_wv_[t] * z(i, l, f, grad, hess);
    }
    out[l] += acc;
  }
}

double SecondOrderStabilization::energy(const double* f, const double* grad, const double* hess) const {
  // parallel_sums: the same sum for any thread count (a reduction clause is not).
  return parallel_sums<1>(op_->rows(), [&](std::size_t i, double* acc) {
    if (!(cv_[i] > 0.0)) return;
    double s = 0.0;
    for (Offset k = op_->offsets()[i]; k < op_->offsets()[i + 1]; ++k) {
      const double zk = z(i, op_->cols()[k], f, grad, hess);
      s += wv_[k] * zk * zk;
    }
    acc[0] += 0.5 * cv_[i] * s;
  })[0];
}

void SecondOrderStabilization::add_row(std::size_t r, const std::function<void(ParticleId, double)>& add) const {
  const SecondOrderOperator& op = *op_;
  const int d = dim_, m = nb_ - d;
  // a_ik = (g_ik ; h_ik), and s_i = sum_k a_ik = -(the diagonals).
  auto a_dot = [&](const double* p, Offset k) {
    double s = 0.0;
    for (int q = 0; q < d; ++q) s += p[q] * op.gradient_weight(k)[q];
    for (int q = 0; q < m; ++q) s += p[d + q] * op.hessian_weight(k)[q];
    return s;
  };
  auto s_dot = [&](const double* p, std::size_t i) {
    double s = 0.0;
    for (int q = 0; q < d; ++q) s -= p[q] * op.gradient_diagonal(i)[q];
    for (int q = 0; q < m; ++q) s -= p[d + q] * op.hessian_diagonal(i)[q];
    return s;
  };
  // Row r of the block of centre r.
  if (cv_[r] > 0.0) {
    const double* b = b_.data() + r * nb_;
    double wsum = 0.0;
    for (Offset k = op.offsets()[r]; k < op.offsets()[r + 1]; ++k) {
      wsum += wv_[k];
      add(op.cols()[k], -cv_[r] * (wv_[k] - a_dot(b, k)));
    }
    add(static_cast<ParticleId>(r), cv_[r] * (wsum - s_dot(b, r)));
  }
  // Row r of the block of every centre i whose family holds r.
  double p[9];
  for (Offset t = op.dual_offsets()[r]; t < op.dual_offsets()[r + 1]; ++t) {
    const ParticleId i = op.dual_cols()[t];
    if (!(cv_[i] > 0.0)) continue;
    const double c = cv_[i] * t_wv_[t];
    basis(i, r, p);
    add(static_cast<ParticleId>(r), c);
    add(i, -c * (1.0 - s_dot(p, i)));
    for (Offset k = op.offsets()[i]; k < op.offsets()[i + 1]; ++k) add(op.cols()[k], -c * a_dot(p, k));
  }
}

std::size_t SecondOrderStabilization::memory_bytes() const {
  return (x_.size() + cv_.size() + wv_.size() + t_wv_.size() + b_.size() + r_.size()) * sizeof(double);
}

ScalarCsr assemble_second_order_stabilization(const SecondOrderStabilization& S, std::size_t n) {
  return assemble_rows(n, [&S](std::size_t r, RowAccumulator& acc) {
    S.add_row(r, [&acc](ParticleId c, double v) { *acc.at(c) += v; });
  });
}

std::vector<double> second_order_stabilization_coefficients(const PointCloud& cloud,
                                                            const SecondOrderOperator& op,
                                                            const BondWeights& weights, double c_hg,
                                                            double rigidity,
                                                            const std::vector<double>& area) {
  const int d = cloud.dim;
  std::vector<double> cv(op.rows(), 0.0);
  for (std::size_t i = 0; i < op.rows(); ++i) {
    if (!(area[i] > 0.0) || !(c_hg > 0.0)) continue;
    double q = 0.0;
    for (Offset k = op.offsets()[i]; k < op.offsets()[i + 1]; ++k) {
      double r2 = 0.0;
      for (int a = 0; a < d; ++a) {
        const double e = cloud.x[static_cast<std::size_t>(op.cols()[k]) * d + a] - cloud.x[i * d + a];
        r2 += e * e;
      }
      q += weights.wv[k] * r2 * r2 / 4.0;
    }
    cv[i] = c_hg * rigidity * area[i] / q;
  }
  return cv;
}

}  // namespace perinom

#include "perinom/operators/second_order_stabilization.hpp"

#include <algorithm>
#include <stdexcept>

#include "operator_access.hpp"
#include "perinom/core/parallel.hpp"
#include "perinom/operators/stabilization.hpp"

namespace perinom {

SecondOrderStabilization::SecondOrderStabilization(const PointCloud& cloud, const NonlocalOperator& op,
                                                   std::vector<double> cv)
    : dim_(cloud.dim), nb_(cloud.dim + op.hessian_terms()), op_(&op), x_(cloud.x), cv_(std::move(cv)),
      wv_(&OperatorAccess::wv(op)), t_wv_(op.bonds()), b_(op.rows() * nb_, 0.0), r_(op.rows(), 0.0) {
  if (!op.has_hessian())
    throw std::invalid_argument("SecondOrderStabilization: the operator has no Hessian weights");
  const BondGraph& g = op.graph();
  for (Offset k = 0; k < static_cast<Offset>(op.bonds()); ++k) t_wv_[g.dual_entry(k)] = wv(k);
  double p[9];
  for (std::size_t i = 0; i < op.rows(); ++i) {
    if (op.is_detached(i)) cv_[i] = 0.0;
    for (Offset k = g.begin(i); k < g.end(i); ++k) {
      basis(i, g.col(k), p);
      for (int s = 0; s < nb_; ++s) b_[i * nb_ + s] += wv(k) * p[s];
    }
  }
}

void SecondOrderStabilization::refresh_rows(const std::vector<ParticleId>& rows, const std::vector<double>& cv) {
  const BondGraph& g = op_->graph();
  double p[9];
  for (const ParticleId i : rows) {
    cv_[i] = op_->is_detached(i) ? 0.0 : cv[i];
    double* b = b_.data() + static_cast<std::size_t>(i) * nb_;
    std::fill(b, b + nb_, 0.0);
    for (Offset k = g.begin(i); k < g.end(i); ++k) {
      t_wv_[g.dual_entry(k)] = this->wv(k);
      basis(i, g.col(k), p);
      for (int s = 0; s < nb_; ++s) b[s] += wv(k) * p[s];
    }
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
  const Offset* off = op_->graph().offsets().data();
  const ParticleId* col = op_->graph().cols().data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double r = 0.0;
    if (cv_[i] > 0.0)
      for (Offset k = off[i]; k < off[i + 1]; ++k) r += wv(k) * z(i, col[k], f, grad, hess);
    r_[i] = cv_[i] * r;
  }
  const Offset* t_off = op_->graph().dual_offsets().data();
  const ParticleId* t_col = op_->graph().dual_cols().data();
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
    for (Offset k = op_->graph().begin(i); k < op_->graph().end(i); ++k) {
      const double zk = z(i, op_->graph().col(k), f, grad, hess);
      s += wv(k) * zk * zk;
    }
    acc[0] += 0.5 * cv_[i] * s;
  })[0];
}

void SecondOrderStabilization::add_row(std::size_t r, const std::function<void(ParticleId, double)>& add) const {
  const NonlocalOperator& op = *op_;
  const BondGraph& g = op.graph();
  using A = OperatorAccess;
  const int d = dim_, m = nb_ - d;
  // a_ik = (g_ik ; h_ik), and s_i = sum_k a_ik = -(the diagonals).
  auto a_dot = [&](const double* p, Offset k) {
    double s = 0.0;
    for (int q = 0; q < d; ++q) s += p[q] * A::weight(op, k, q);
    for (int q = 0; q < m; ++q) s += p[d + q] * A::weight(op, k, q, Derivative::hessian);
    return s;
  };
  auto s_dot = [&](const double* p, std::size_t i) {
    double s = 0.0;
    for (int q = 0; q < d; ++q) s -= p[q] * A::diagonal(op, i)[q];
    for (int q = 0; q < m; ++q) s -= p[d + q] * A::diagonal(op, i, Derivative::hessian)[q];
    return s;
  };
  // Row r of the block of centre r.
  if (cv_[r] > 0.0) {
    const double* b = b_.data() + r * nb_;
    double wsum = 0.0;
    for (Offset k = g.begin(r); k < g.end(r); ++k) {
      wsum += wv(k);
      if (g.alive(k)) add(g.col(k), -cv_[r] * (wv(k) - a_dot(b, k)));
    }
    add(static_cast<ParticleId>(r), cv_[r] * (wsum - s_dot(b, r)));
  }
  // Row r of the block of every centre i whose family holds r.
  double p[9];
  for (Offset t = g.dual_begin(r); t < g.dual_end(r); ++t) {
    const ParticleId i = g.dual_col(t);
    if (!(cv_[i] > 0.0) || !g.dual_alive(t)) continue;
    const double c = cv_[i] * t_wv_[t];
    basis(i, r, p);
    add(static_cast<ParticleId>(r), c);
    add(i, -c * (1.0 - s_dot(p, i)));
    for (Offset k = g.begin(i); k < g.end(i); ++k)
      if (g.alive(k)) add(g.col(k), -c * a_dot(p, k));
  }
}

std::size_t SecondOrderStabilization::memory_bytes() const {
  return (x_.size() + cv_.size() + t_wv_.size() + b_.size() + r_.size()) * sizeof(double);
}

ScalarCsr assemble_second_order_stabilization(const SecondOrderStabilization& S, std::size_t n) {
  return assemble_rows(n, [&S](std::size_t r, RowAccumulator& acc) {
    S.add_row(r, [&acc](ParticleId c, double v) { *acc.at(c) += v; });
  });
}

void refresh_second_order_stabilization(ScalarCsr& A, const SecondOrderStabilization& S, const BondGraph& graph,
                                        const std::vector<ParticleId>& rows) {
  reassemble_rows(A, stabilization_rows(graph, rows), [&S](std::size_t r, RowAccumulator& acc) {
    S.add_row(r, [&acc](ParticleId c, double v) { *acc.at(c) += v; });
  });
}

std::vector<double> second_order_stabilization_coefficients(const PointCloud& cloud, const NonlocalOperator& op,
                                                            double c_hg, double rigidity,
                                                            const std::vector<double>& area) {
  const int d = cloud.dim;
  const BondGraph& g = op.graph();
  const std::vector<double>& wv = OperatorAccess::wv(op);
  std::vector<double> cv(op.rows(), 0.0);
  for (std::size_t i = 0; i < op.rows(); ++i) {
    if (!(area[i] > 0.0) || !(c_hg > 0.0) || op.is_detached(i)) continue;
    double q = 0.0;
    g.for_each_live(i, [&](Offset k, ParticleId j) {
      double r2 = 0.0;
      for (int a = 0; a < d; ++a) {
        const double e = cloud.x[static_cast<std::size_t>(j) * d + a] - cloud.x[i * d + a];
        r2 += e * e;
      }
      q += wv[k] * r2 * r2 / 4.0;
    });
    cv[i] = c_hg * rigidity * area[i] / q;
  }
  return cv;
}

}  // namespace perinom

#include "perinom/operators/consistent_gradient.hpp"

#include <algorithm>
#include <cmath>

#include "perinom/core/parallel.hpp"
#include "perinom/core/thread_governor.hpp"
#include "operator_access.hpp"

namespace perinom {
namespace {

/// The operator L gamma = Delta(gamma)^T V of the header, with the scratch it needs.
/// On a rank's share, the corrections are those of the owned and near rows (`rows`) and L's
/// rows those of the owned unknowns (`unknowns`); the other entries are left zero.
class ConstraintOperator {
 public:
  ConstraintOperator(const PointCloud& cloud, const Families& families, const BondWeights& weights,
                     const NonlocalOperator& G1, std::size_t rows, std::size_t unknowns)
      : cloud_(cloud), families_(families), weights_(weights), G1_(G1), dual_(dual_support(families)),
        rows_(rows), unknowns_(unknowns), a_(cloud.size() * cloud.dim), delta_(families.bonds()),
        rowsum_(cloud.size()) {}

  /// delta[k] = V_i w_ij V_j r_ij for bond k = (i, j), and rowsum_i = sum_j delta_ij.
  void corrections(const double* gamma) {
    G1_.apply(gamma, 1, a_.data());
    const int d = cloud_.dim;
    const double* x = cloud_.x.data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < rows_; ++i) {
      double sum = 0.0;
      const double* a = a_.data() + i * d;
      for (Offset k = families_.begin(i); k < families_.end(i); ++k) {
        const ParticleId j = families_.neighbors[k];
        double r = gamma[j] - gamma[i];
        for (int c = 0; c < d; ++c) r -= (x[j * d + c] - x[i * d + c]) * a[c];
        delta_[k] = cloud_.volume[i] * weights_.wv[k] * r;
        sum += delta_[k];
      }
      rowsum_[i] = sum;
    }
  }

  /// out = L gamma: column sums sum_i V_i Delta_ij, the diagonal Delta_jj = -rowsum_j included.
  void apply(const double* gamma, double* out) {
    corrections(gamma);
#pragma omp parallel for schedule(static)
    for (std::size_t j = 0; j < unknowns_; ++j) {
      double s = -cloud_.volume[j] * rowsum_[j];
      for (Offset t = dual_.offsets[j]; t < dual_.offsets[j + 1]; ++t)
        s += cloud_.volume[dual_.neighbors[t]] * delta_[dual_.bond[t]];
      out[j] = s;
    }
  }

  /// An estimate of L's diagonal (the fit's share dropped), for Jacobi preconditioning.
  std::vector<double> diagonal() const {
    std::vector<double> dg(cloud_.size(), 1.0);
    for (std::size_t j = 0; j < unknowns_; ++j) {
      double s = 0.0;
      const double vj = cloud_.volume[j];
      for (Offset k = families_.begin(j); k < families_.end(j); ++k) s += vj * vj * weights_.wv[k];
      for (Offset t = dual_.offsets[j]; t < dual_.offsets[j + 1]; ++t) {
        const double vi = cloud_.volume[dual_.neighbors[t]];
        s += vi * vi * weights_.wv[dual_.bond[t]];
      }
      dg[j] = s;
    }
    return dg;
  }

  const std::vector<double>& delta() const { return delta_; }

 private:
  const PointCloud& cloud_;
  const Families& families_;
  const BondWeights& weights_;
  const NonlocalOperator& G1_;
  DualSupport dual_;
  std::size_t rows_, unknowns_;
  std::vector<double> a_, delta_, rowsum_;
};

/// The whole body, or a rank's share of it: which entries are unknowns, and how a field's
/// ghost entries and a sum over the ranks are had.
struct Share {
  std::size_t unknowns, rows;
  const CorrectionShare* ranks;

  double dot(const std::vector<double>& a, const std::vector<double>& b) const {
    double s = parallel_sums<1>(unknowns, [&](std::size_t k, double* acc) { acc[0] += a[k] * b[k]; })[0];
    sum(&s, 1);
    return s;
  }
  void sum(double* values, int count) const {
    if (ranks) ranks->sum(values, count);
  }
  void exchange(std::vector<double>& field) const {
    if (ranks) ranks->exchange(field.data());
  }
};

/// An orthonormal basis of L's null space, the linear fields at the particles (in coordinates
/// centred and scaled to the cloud, for a well-conditioned Gram-Schmidt).
std::vector<std::vector<double>> null_space(const PointCloud& cloud, const Share& share) {
  const int d = cloud.dim, n = static_cast<int>(cloud.size()), own = static_cast<int>(share.unknowns);
  double total = own;
  share.sum(&total, 1);
  double centre[3] = {0, 0, 0}, scale = 0.0;
  for (int i = 0; i < own; ++i)
    for (int a = 0; a < d; ++a) centre[a] += cloud.x[i * d + a] / total;
  share.sum(centre, 3);
  for (int i = 0; i < own; ++i)
    for (int a = 0; a < d; ++a) scale = std::max(scale, std::abs(cloud.x[i * d + a] - centre[a]));
  if (share.ranks) share.ranks->max(&scale, 1);
  std::vector<std::vector<double>> q(d + 1, std::vector<double>(n, 1.0));
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < d; ++a) q[a + 1][i] = (cloud.x[i * d + a] - centre[a]) / scale;
  for (std::size_t v = 0; v < q.size(); ++v) {
    for (int pass = 0; pass < 2; ++pass)
      for (std::size_t u = 0; u < v; ++u) {
        const double c = share.dot(q[v], q[u]);
        for (int i = 0; i < n; ++i) q[v][i] -= c * q[u][i];
      }
    const double norm = std::sqrt(share.dot(q[v], q[v]));
    for (int i = 0; i < n; ++i) q[v][i] /= norm;
  }
  return q;
}

void project_out(const std::vector<std::vector<double>>& null, const Share& share, std::vector<double>& v) {
  for (const auto& q : null) {
    const double c = share.dot(v, q);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] -= c * q[i];
  }
}

}  // namespace

std::vector<double> consistent_gradient_weights(const PointCloud& cloud, const Families& families,
                                                const BondWeights& weights, const NonlocalOperator& G1,
                                                const NonlocalOperator& G, const std::vector<double>& c,
                                                const ConsistencyOptions& options, ConsistencyReport* report) {
  const int d = cloud.dim;
  const std::size_t n = cloud.size();
  std::vector<double> g(families.bonds() * d);
  for (std::size_t k = 0; k < families.bonds(); ++k)
    for (int b = 0; b < d; ++b) g[k * d + b] = OperatorAccess::weight(G, static_cast<Offset>(k), b);
  // The whole body: every particle is an unknown and a row. A rank's share: its own particles
  // are the unknowns, and the rows are theirs and the near ghosts' (whose families are whole).
  const CorrectionShare* ranks = options.ranks;
  const Share share{ranks ? ranks->owned : n, ranks ? ranks->owned + ranks->near : n, ranks};
  ConstraintOperator L(cloud, families, weights, G1, share.rows, share.unknowns);
  const auto null = null_space(cloud, share);
  const std::vector<double> diag = L.diagonal();
  // G^T V 1 per component: the column sums of the current weights, the diagonal included
  // (an owned column's sum reads owned and near rows only).
  std::vector<double> current(n * d, 0.0);
  for (std::size_t i = 0; i < share.rows; ++i)
    for (Offset k = families.begin(i); k < families.end(i); ++k)
      for (int b = 0; b < d; ++b) {
        current[families.neighbors[k] * d + b] += cloud.volume[i] * g[k * d + b];
        current[i * d + b] -= cloud.volume[i] * g[k * d + b];
      }
  std::vector<double> out = g;
  ConsistencyReport rep;
  rep.converged = true;
  std::vector<double> e(n), x(n), r(n), z(n), p(n), q(n);
  double change = 0.0, size = 0.0;
  ThreadGovernor governor;
  for (int b = 0; b < d; ++b) {
    for (std::size_t j = 0; j < n; ++j) e[j] = j < share.unknowns ? c[j * d + b] - current[j * d + b] : 0.0;
    const double e_norm = std::sqrt(share.dot(e, e));
    if (!(e_norm > 0.0)) continue;
    std::vector<double> consistent = e;
    project_out(null, share, consistent);
    double removed = 0.0;
    for (std::size_t j = 0; j < share.unknowns; ++j) removed += (e[j] - consistent[j]) * (e[j] - consistent[j]);
    share.sum(&removed, 1);
    rep.rhs_defect = std::max(rep.rhs_defect, std::sqrt(removed) / e_norm);
    // Preconditioned CG on the consistent singular system L gamma = e, restarted from the
    // true residual: the recursive one drifts from it by rounding (about 1e-11 relative on
    // long solves), and a restart removes that floor.
    std::fill(x.begin(), x.end(), 0.0);
    r = consistent;
    const double r0 = std::sqrt(share.dot(r, r));
    double true_res = r0;
    int it = 0;
    for (int restart = 0; restart < 4 && true_res > options.tolerance * r0; ++restart) {
      for (std::size_t j = 0; j < n; ++j) z[j] = r[j] / diag[j];
      p = z;
      double rz = share.dot(r, z), rnorm = true_res;
      while (rnorm > options.tolerance * r0 && it < options.max_iterations) {
        governor.tick();
        share.exchange(p);
        L.apply(p.data(), q.data());
        const double alpha = rz / share.dot(p, q);
        for (std::size_t j = 0; j < n; ++j) x[j] += alpha * p[j], r[j] -= alpha * q[j];
        ++it;
        rnorm = std::sqrt(share.dot(r, r));
        for (std::size_t j = 0; j < n; ++j) z[j] = r[j] / diag[j];
        const double rz_next = share.dot(r, z);
        const double beta = rz_next / rz;
        rz = rz_next;
        for (std::size_t j = 0; j < n; ++j) p[j] = z[j] + beta * p[j];
      }
      share.exchange(x);
      L.apply(x.data(), q.data());
      for (std::size_t j = 0; j < n; ++j) r[j] = consistent[j] - q[j];
      project_out(null, share, r);
      true_res = std::sqrt(share.dot(r, r));
    }
    share.exchange(x);
    L.apply(x.data(), q.data());  // leaves the corrections of x in L.delta()
    rep.iterations = std::max(rep.iterations, it);
    rep.residual = std::max(rep.residual, true_res / e_norm);
    if (!(true_res <= options.converged_tolerance * r0)) rep.converged = false;
    const auto& delta = L.delta();  // of the last apply: the corrections of x
    const std::size_t own_bonds = share.unknowns > 0 ? std::size_t(families.end(share.unknowns - 1)) : 0;
    for (std::size_t k = 0; k < delta.size(); ++k) {
      out[k * d + b] += delta[k];
      if (k >= own_bonds) continue;
      change += delta[k] * delta[k];
      size += g[k * d + b] * g[k * d + b];
    }
  }
  double sizes[2] = {change, size};
  share.sum(sizes, 2);
  change = sizes[0], size = sizes[1];
  rep.relative_change = size > 0.0 ? std::sqrt(change / size) : 0.0;
  if (report) *report = rep;
  return out;
}

}  // namespace perinom

#include "perinom/operators/stabilization.hpp"

namespace perinom {
namespace {

double dot(const double* a, const double* b, int d) {
  double s = 0.0;
  for (int k = 0; k < d; ++k) s += a[k] * b[k];
  return s;
}

// z = u_j - u_i - H_i (x_j - x_i) for one bond, d components.
template <int D>
inline void bond_z(const double* ui, const double* uj, const double* Hi, const double* xi,
                   const double* xj, double* z, double* xi_ij) {
  for (int b = 0; b < D; ++b) xi_ij[b] = xj[b] - xi[b];
  for (int a = 0; a < D; ++a) {
    double s = uj[a] - ui[a];
    for (int b = 0; b < D; ++b) s -= Hi[a * D + b] * xi_ij[b];
    z[a] = s;
  }
}

template <int D>
void row_pass(std::size_t n, const Offset* off, const ParticleId* col, const double* wv,
              const double* cv, const double* x, const double* u, const double* H, double* B,
              double* r) {
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double Bi[D * D] = {}, ri[D] = {}, z[D], xi_ij[D];
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const std::size_t j = col[k];
      bond_z<D>(u + i * D, u + j * D, H + i * D * D, x + i * D, x + j * D, z, xi_ij);
      const double beta = cv[i] * wv[k];
      for (int a = 0; a < D; ++a) {
        ri[a] += beta * z[a];
        for (int b = 0; b < D; ++b) Bi[a * D + b] += beta * z[a] * xi_ij[b];
      }
    }
    for (int k = 0; k < D * D; ++k) B[i * D * D + k] = Bi[k];
    for (int a = 0; a < D; ++a) r[i * D + a] = ri[a];
  }
}

template <int D>
void dual_pass(std::size_t n, const Offset* off, const ParticleId* col, const double* t_wv,
               const double* cv, const double* x, const double* u, const double* H,
               const double* r, double* out) {
#pragma omp parallel for schedule(static)
  for (std::size_t l = 0; l < n; ++l) {
    double acc[D], z[D], xi_il[D];
    for (int a = 0; a < D; ++a) acc[a] = -r[l * D + a];
    for (Offset k = off[l]; k < off[l + 1]; ++k) {
      const std::size_t i = col[k];  // l is in H_i
      bond_z<D>(u + i * D, u + l * D, H + i * D * D, x + i * D, x + l * D, z, xi_il);
      const double beta = cv[i] * t_wv[k];
      for (int a = 0; a < D; ++a) acc[a] += beta * z[a];
    }
    for (int a = 0; a < D; ++a) out[l * D + a] += acc[a];
  }
}

}  // namespace

Stabilization::Stabilization(const PointCloud& cloud, const Families& families,
                             const BondWeights& weights, const GradientOperator& G,
                             const std::vector<double>& coefficient)
    : dim_(cloud.dim), G_(&G), x_(cloud.x), cv_(cloud.size()), wv_(weights.wv) {
  for (std::size_t i = 0; i < cloud.size(); ++i) cv_[i] = coefficient[i] * cloud.volume[i];
  const DualSupport dual = dual_support(families);
  t_wv_.resize(dual.bond.size());
  for (std::size_t s = 0; s < dual.bond.size(); ++s) t_wv_[s] = wv_[dual.bond[s]];
}

void Stabilization::bond_terms(const double* u, const double* H, double* B, double* r) const {
  const std::size_t n = cv_.size();
  const Offset* off = G_->offsets().data();
  const ParticleId* col = G_->cols().data();
  if (dim_ == 2) row_pass<2>(n, off, col, wv_.data(), cv_.data(), x_.data(), u, H, B, r);
  else row_pass<3>(n, off, col, wv_.data(), cv_.data(), x_.data(), u, H, B, r);
}

void Stabilization::add_direct(const double* u, const double* H, const double* r, double* out) const {
  const std::size_t n = cv_.size();
  const Offset* off = G_->dual_offsets().data();
  const ParticleId* col = G_->dual_cols().data();
  if (dim_ == 2) dual_pass<2>(n, off, col, t_wv_.data(), cv_.data(), x_.data(), u, H, r, out);
  else dual_pass<3>(n, off, col, t_wv_.data(), cv_.data(), x_.data(), u, H, r, out);
}

void Stabilization::add_row(std::size_t r, RowAccumulator& acc, int copies) const {
  const int d = dim_;
  const GradientOperator& G = *G_;
  auto add = [&](ParticleId j, double v) {
    double* block = acc.at(j);
    for (int k = 0; k < copies; ++k) block[k * (copies + 1)] += v;
  };
  const double* xr = x_.data() + r * d;
  // Row r of M_r (r is the centre): A_r = -sum_k a_rk, a_rk = w_rk V_k xi_rk.
  {
    const double scale = cv_[r];
    double s[3] = {0, 0, 0}, wsum = 0.0;
    for (Offset k = G.offsets()[r]; k < G.offsets()[r + 1]; ++k) {
      const double* xj = x_.data() + static_cast<std::size_t>(G.cols()[k]) * d;
      for (int a = 0; a < d; ++a) s[a] -= wv_[k] * (xj[a] - xr[a]);
      wsum += wv_[k];
    }
    add(static_cast<ParticleId>(r), scale * (wsum - dot(s, G.diagonal(r), d)));
    for (Offset k = G.offsets()[r]; k < G.offsets()[r + 1]; ++k)
      add(G.cols()[k], scale * (-wv_[k] - dot(s, G.weight(k).data(), d)));
  }
  // Row r of M_i for every i whose family holds r: A_r = a_ir = w_ir V_r xi_ir.
  for (Offset t = G.dual_offsets()[r]; t < G.dual_offsets()[r + 1]; ++t) {
    const ParticleId i = G.dual_cols()[t];
    const double scale = cv_[i];
    const double* xi = x_.data() + static_cast<std::size_t>(i) * d;
    double a[3] = {0, 0, 0};
    for (int c = 0; c < d; ++c) a[c] = t_wv_[t] * (xr[c] - xi[c]);
    add(static_cast<ParticleId>(r), scale * t_wv_[t]);
    add(i, scale * (-t_wv_[t] - dot(a, G.diagonal(i), d)));
    for (Offset k = G.offsets()[i]; k < G.offsets()[i + 1]; ++k) add(G.cols()[k], -scale * dot(a, G.weight(k).data(), d));
  }
}

std::size_t Stabilization::memory_bytes() const {
  return (x_.size() + cv_.size() + wv_.size() + t_wv_.size()) * sizeof(double);
}

ScalarCsr assemble_stabilization(const Stabilization& S, std::size_t n) {
  return assemble_rows(n, [&S](std::size_t r, RowAccumulator& acc) { S.add_row(r, acc, 1); });
}

std::vector<double> stabilization_coefficients(const BondWeights& weights, int d, double c_hg,
                                               double mu) {
  const std::size_t n = weights.shape.size() / (d * d);
  std::vector<double> c(n);
  for (std::size_t i = 0; i < n; ++i) {
    double tr = 0.0;
    for (int a = 0; a < d; ++a) tr += weights.shape[i * d * d + a * d + a];
    c[i] = c_hg * 2.0 * mu / tr;
  }
  return c;
}

}  // namespace perinom

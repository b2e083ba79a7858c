#include "perinom/operators/stabilization.hpp"

#include <algorithm>

#include "operator_access.hpp"

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

Stabilization::Stabilization(const PointCloud& cloud, const NonlocalOperator& G, double modulus)
    : dim_(cloud.dim), modulus_(modulus), G_(&G), x_(cloud.x), cv_(cloud.size()), wv_(OperatorAccess::wv(G)),
      t_wv_(wv_.size()), volume_(cloud.volume) {
  const BondGraph& g = G.graph();
  for (std::size_t i = 0; i < cloud.size(); ++i) refresh_coefficient(i, volume_);
  for (std::size_t k = 0; k < wv_.size(); ++k) {
    if (!g.alive(static_cast<Offset>(k))) wv_[k] = 0.0;
    t_wv_[g.dual_entry(static_cast<Offset>(k))] = wv_[k];
  }
}

void Stabilization::refresh_coefficient(std::size_t i, const std::vector<double>& volume) {
  const int d = dim_;
  double tr = 0.0;
  for (int a = 0; a < d; ++a) tr += G_->shape(i)[a * d + a];
  cv_[i] = G_->is_detached(i) || !(tr > 0.0) ? 0.0 : modulus_ / tr * volume[i];
}

void Stabilization::refresh_rows(const std::vector<ParticleId>& rows) {
  const BondGraph& g = G_->graph();
  const std::vector<double>& wv = OperatorAccess::wv(*G_);
  // Each row writes its own bonds, in both orders (distinct dual entries).
#pragma omp parallel for schedule(dynamic, 16) if (rows.size() > 64)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const ParticleId i = rows[r];
    refresh_coefficient(i, volume_);
    for (Offset k = g.begin(i); k < g.end(i); ++k) t_wv_[g.dual_entry(k)] = wv_[k] = g.alive(k) ? wv[k] : 0.0;
  }
}

void Stabilization::bond_terms(const double* u, const double* H, double* B, double* r) const {
  const std::size_t n = cv_.size();
  const Offset* off = G_->graph().offsets().data();
  const ParticleId* col = G_->graph().cols().data();
  if (dim_ == 2) row_pass<2>(n, off, col, wv_.data(), cv_.data(), x_.data(), u, H, B, r);
  else row_pass<3>(n, off, col, wv_.data(), cv_.data(), x_.data(), u, H, B, r);
}

void Stabilization::add_direct(const double* u, const double* H, const double* r, double* out) const {
  const std::size_t n = cv_.size();
  const Offset* off = G_->graph().dual_offsets().data();
  const ParticleId* col = G_->graph().dual_cols().data();
  if (dim_ == 2) dual_pass<2>(n, off, col, t_wv_.data(), cv_.data(), x_.data(), u, H, r, out);
  else dual_pass<3>(n, off, col, t_wv_.data(), cv_.data(), x_.data(), u, H, r, out);
}

void Stabilization::add_row(std::size_t r, RowAccumulator& acc, int copies) const {
  const int d = dim_;
  const NonlocalOperator& G = *G_;
  const BondGraph& g = G.graph();
  using A = OperatorAccess;
  double scratch[6];
  auto add = [&](ParticleId j, double v) {
    double* block = acc.at(j);
    for (int k = 0; k < copies; ++k) block[k * (copies + 1)] += v;
  };
  const double* xr = x_.data() + r * d;
  // Row r of M_r (r is the centre): A_r = -sum_k a_rk, a_rk = w_rk V_k xi_rk.
  if (cv_[r] > 0.0) {
    const double scale = cv_[r];
    double s[3] = {0, 0, 0}, wsum = 0.0;
    for (Offset k = g.begin(r); k < g.end(r); ++k) {
      const double* xj = x_.data() + static_cast<std::size_t>(g.col(k)) * d;
      for (int a = 0; a < d; ++a) s[a] -= wv_[k] * (xj[a] - xr[a]);
      wsum += wv_[k];
    }
    add(static_cast<ParticleId>(r), scale * (wsum - dot(s, A::diagonal(G, r), d)));
    for (Offset k = g.begin(r); k < g.end(r); ++k)
      if (g.alive(k)) add(g.col(k), scale * (-wv_[k] - dot(s, A::weights(G, k, scratch), d)));
  }
  // Row r of M_i for every i whose family holds r: A_r = a_ir = w_ir V_r xi_ir.
  for (Offset t = g.dual_begin(r); t < g.dual_end(r); ++t) {
    const ParticleId i = g.dual_col(t);
    const double scale = cv_[i];
    if (!g.dual_alive(t) || !(scale > 0.0)) continue;
    const double* xi = x_.data() + static_cast<std::size_t>(i) * d;
    double a[3] = {0, 0, 0};
    for (int c = 0; c < d; ++c) a[c] = t_wv_[t] * (xr[c] - xi[c]);
    add(static_cast<ParticleId>(r), scale * t_wv_[t]);
    add(i, scale * (-t_wv_[t] - dot(a, A::diagonal(G, i), d)));
    for (Offset k = g.begin(i); k < g.end(i); ++k)
      if (g.alive(k)) add(g.col(k), -scale * dot(a, A::weights(G, k, scratch), d));
  }
}

std::size_t Stabilization::memory_bytes() const {
  return (x_.size() + cv_.size() + wv_.size() + t_wv_.size() + volume_.size()) * sizeof(double);
}

ScalarCsr assemble_stabilization(const Stabilization& S, std::size_t n) {
  return assemble_rows(n, [&S](std::size_t r, RowAccumulator& acc) { S.add_row(r, acc, 1); });
}

std::vector<ParticleId> stabilization_rows(const BondGraph& graph, const std::vector<ParticleId>& rows) {
  std::vector<ParticleId> out;
  for (const ParticleId i : rows) {
    out.push_back(i);
    for (Offset k = graph.begin(i); k < graph.end(i); ++k) out.push_back(graph.col(k));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void refresh_stabilization(ScalarCsr& S0, const Stabilization& S, const BondGraph& graph,
                           const std::vector<ParticleId>& rows) {
  reassemble_rows(S0, stabilization_rows(graph, rows),
                  [&S](std::size_t r, RowAccumulator& acc) { S.add_row(r, acc, 1); });
}

std::vector<double> stabilization_coefficients(const NonlocalOperator& G, double c_hg, double mu) {
  const int d = G.dim();
  std::vector<double> c(G.rows(), 0.0);
  for (std::size_t i = 0; i < G.rows(); ++i) {
    double tr = 0.0;
    for (int a = 0; a < d; ++a) tr += G.shape(i)[a * d + a];
    if (!G.is_detached(i) && tr > 0.0) c[i] = c_hg * 2.0 * mu / tr;
  }
  return c;
}

}  // namespace perinom

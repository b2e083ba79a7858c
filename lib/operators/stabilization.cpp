#include "perinom/operators/stabilization.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "operator_access.hpp"
#include "perinom/core/parallel.hpp"

namespace perinom {
namespace {

double dot(const double* a, const double* b, int n) {
  double s = 0.0;
  for (int k = 0; k < n; ++k) s += a[k] * b[k];
  return s;
}

// p_ij of the fit of basis size NB in D dimensions: xi = x_j - x_i, then (order 2) the
// quadratic terms, 1/2 xi_a^2 on the diagonal.
template <int D, int NB>
inline void basis(const double* xi, const double* xj, double* p) {
  for (int a = 0; a < D; ++a) p[a] = xj[a] - xi[a];
  if constexpr (NB > D) {
    int r = D;
    for (int a = 0; a < D; ++a)
      for (int b = a; b < D; ++b) p[r++] = a == b ? 0.5 * p[a] * p[a] : p[a] * p[b];
  }
}

// z = u_j - u_i - D_i p for one bond, C components; g_i (C x D) and h_i (C x (NB - D)) are
// particle i's derivatives.
template <int D, int NB, int C>
inline void bond_z(const double* ui, const double* uj, const double* gi, const double* hi, const double* p,
                   double* z) {
  constexpr int M = NB - D;
  for (int c = 0; c < C; ++c) {
    double s = uj[c] - ui[c];
    for (int q = 0; q < D; ++q) s -= gi[c * D + q] * p[q];
    if constexpr (M > 0)
      for (int q = 0; q < M; ++q) s -= hi[c * M + q] * p[D + q];
    z[c] = s;
  }
}

// The arrays of one field: u (N x C), its gradient (N x C x D) and Hessian (N x C x M).
struct Field {
  const double* u;
  const double* grad;
  const double* hess;
};

template <int D, int NB, int C>
inline void z_of(const Field& f, const double* x, std::size_t i, std::size_t j, double* p, double* z) {
  constexpr int M = NB - D;
  basis<D, NB>(x + i * D, x + j * D, p);
  bond_z<D, NB, C>(f.u + i * C, f.u + j * C, f.grad + i * C * D, M > 0 ? f.hess + i * C * M : nullptr, p, z);
}

template <int D, int NB, int C, bool WithB>
void row_pass(const BondGraph& g, const double* wv, const double* cv, const double* x, const Field& f, double* B,
              double* r) {
  const std::size_t n = g.rows();
  const Offset* off = g.offsets().data();
  const ParticleId* col = g.cols().data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double Bi[C * D] = {}, ri[C] = {}, z[C], p[NB];
    if (cv[i] > 0.0)
      for (Offset k = off[i]; k < off[i + 1]; ++k) {
        z_of<D, NB, C>(f, x, i, col[k], p, z);
        if constexpr (WithB) {  // beta_ij per bond, as B needs it
          const double beta = cv[i] * wv[k];
          for (int c = 0; c < C; ++c) {
            ri[c] += beta * z[c];
            for (int b = 0; b < D; ++b) Bi[c * D + b] += beta * z[c] * p[b];
          }
        } else {  // cv_i once per row
          for (int c = 0; c < C; ++c) ri[c] += wv[k] * z[c];
        }
      }
    if constexpr (WithB)
      for (int k = 0; k < C * D; ++k) B[i * C * D + k] = Bi[k];
    for (int c = 0; c < C; ++c) r[i * C + c] = WithB ? ri[c] : cv[i] * ri[c];
  }
}

template <int D, int NB, int C>
void dual_pass(const BondGraph& g, const double* t_wv, const double* cv, const double* x, const Field& f,
               const double* r, double* out) {
  const std::size_t n = g.rows();
  const Offset* off = g.dual_offsets().data();
  const ParticleId* col = g.dual_cols().data();
#pragma omp parallel for schedule(static)
  for (std::size_t l = 0; l < n; ++l) {
    double acc[C], z[C], p[NB];
    for (int c = 0; c < C; ++c) acc[c] = -r[l * C + c];
    for (Offset t = off[l]; t < off[l + 1]; ++t) {
      const std::size_t i = col[t];  // l is in H_i
      if (!(cv[i] > 0.0)) continue;
      z_of<D, NB, C>(f, x, i, l, p, z);
      const double beta = cv[i] * t_wv[t];
      for (int c = 0; c < C; ++c) acc[c] += beta * z[c];
    }
    for (int c = 0; c < C; ++c) out[l * C + c] += acc[c];
  }
}

template <int D, int NB, int C>
double energy_pass(const BondGraph& g, const double* wv, const double* cv, const double* x, const Field& f) {
  // parallel_sums: the same sum for any thread count (a reduction clause is not).
  return parallel_sums<1>(g.rows(), [&](std::size_t i, double* acc) {
    if (!(cv[i] > 0.0)) return;
    double s = 0.0, z[C], p[NB];
    for (Offset k = g.begin(i); k < g.end(i); ++k) {
      z_of<D, NB, C>(f, x, i, g.col(k), p, z);
      for (int c = 0; c < C; ++c) s += wv[k] * z[c] * z[c];
    }
    acc[0] += 0.5 * cv[i] * s;
  })[0];
}

// The compile-time shape of a pass: D dimensions, basis size NB, C components.
template <int D_, int NB_, int C_>
struct Shape {
  static constexpr int D = D_, NB = NB_, C = C_;
};

// Calls fn(Shape<D, NB, C>{}) for the shapes the library uses: a vector field (C = d) of
// either order, a scalar field of the second-order fit (the plate).
template <class Fn>
auto dispatch(int d, int nb, int components, Fn&& fn) {
  if (d == 2 && nb == 2 && components == 2) return fn(Shape<2, 2, 2>{});
  if (d == 3 && nb == 3 && components == 3) return fn(Shape<3, 3, 3>{});
  if (d == 2 && nb == 5 && components == 2) return fn(Shape<2, 5, 2>{});
  if (d == 3 && nb == 9 && components == 3) return fn(Shape<3, 9, 3>{});
  if (d == 2 && nb == 5 && components == 1) return fn(Shape<2, 5, 1>{});
  if (d == 3 && nb == 9 && components == 1) return fn(Shape<3, 9, 1>{});
  throw std::invalid_argument("Stabilization: a field of " + std::to_string(components) + " components in " +
                              std::to_string(d) + "-D with a basis of " + std::to_string(nb) +
                              " (supported: d components at order 1, 1 or d at order 2)");
}

}  // namespace

Stabilization::Stabilization(const PointCloud& cloud, const NonlocalOperator& fit, StabilizationScale scale)
    : dim_(cloud.dim), nb_(fit.order() == 1 ? cloud.dim : cloud.dim + fit.hessian_terms()), fit_(&fit),
      scale_(std::move(scale)), x_(cloud.x), cv_(cloud.size()), wv_(OperatorAccess::wv(fit)), t_wv_(wv_.size()) {
  if (fit.order() == 2 && !fit.has_hessian())
    throw std::invalid_argument("Stabilization: the second-order fit has no Hessian weights");
  const BondGraph& g = fit.graph();
  for (std::size_t i = 0; i < cloud.size(); ++i) cv_[i] = fit.is_detached(i) ? 0.0 : scale_(i);
  c0_ = cv_;
  for (std::size_t k = 0; k < wv_.size(); ++k) {
    if (!g.alive(static_cast<Offset>(k))) wv_[k] = 0.0;
    t_wv_[g.dual_entry(static_cast<Offset>(k))] = wv_[k];
  }
}

Stabilization::Stabilization(const PointCloud& cloud, const NonlocalOperator& G, double modulus)
    : Stabilization(cloud, G, shape_scale(G, modulus, cloud.volume)) {}

void Stabilization::refresh_row(ParticleId i) {
  const BondGraph& g = fit_->graph();
  const std::vector<double>& wv = OperatorAccess::wv(*fit_);
  c0_[i] = fit_->is_detached(i) ? 0.0 : scale_(i);
  cv_[i] = factor_.empty() ? c0_[i] : factor_[i] * c0_[i];
  for (Offset k = g.begin(i); k < g.end(i); ++k) t_wv_[g.dual_entry(k)] = wv_[k] = g.alive(k) ? wv[k] : 0.0;
}

void Stabilization::set_centre_factors(std::vector<double> factor) {
  if (factor.size() != cv_.size())
    throw std::invalid_argument("Stabilization::set_centre_factors: " + std::to_string(factor.size()) +
                                " factors for " + std::to_string(cv_.size()) + " particles");
  factor_ = std::move(factor);
  for (std::size_t i = 0; i < cv_.size(); ++i) cv_[i] = factor_[i] * c0_[i];
}

void Stabilization::refresh_rows(const std::vector<ParticleId>& rows) {
  // Each row writes its own bonds, in both orders (distinct dual entries).
#pragma omp parallel for schedule(dynamic, 16) if (rows.size() > 64)
  for (std::size_t r = 0; r < rows.size(); ++r) refresh_row(rows[r]);
}

void Stabilization::bond_terms(const double* u, int components, const double* grad, const double* hess, double* B,
                               double* r) const {
  const Field f{u, grad, hess};
  if (B && nb_ != dim_) throw std::invalid_argument("Stabilization::bond_terms: B is first-order only");
  dispatch(dim_, nb_, components, [&](auto s) {
    using S = decltype(s);
    if (B) row_pass<S::D, S::NB, S::C, true>(fit_->graph(), wv_.data(), cv_.data(), x_.data(), f, B, r);
    else row_pass<S::D, S::NB, S::C, false>(fit_->graph(), wv_.data(), cv_.data(), x_.data(), f, B, r);
  });
}

void Stabilization::add_direct(const double* u, int components, const double* grad, const double* hess,
                               const double* r, double* out) const {
  const Field f{u, grad, hess};
  dispatch(dim_, nb_, components, [&](auto s) {
    using S = decltype(s);
    dual_pass<S::D, S::NB, S::C>(fit_->graph(), t_wv_.data(), cv_.data(), x_.data(), f, r, out);
  });
}

void Stabilization::add_force(const double* u, int components, const double* grad, const double* hess,
                              double* out) {
  r_.resize(cv_.size() * static_cast<std::size_t>(components));
  bond_terms(u, components, grad, hess, nullptr, r_.data());
  add_direct(u, components, grad, hess, r_.data(), out);
}

double Stabilization::energy(const double* u, int components, const double* grad, const double* hess) const {
  const Field f{u, grad, hess};
  return dispatch(dim_, nb_, components, [&](auto s) {
    using S = decltype(s);
    return energy_pass<S::D, S::NB, S::C>(fit_->graph(), wv_.data(), cv_.data(), x_.data(), f);
  });
}

const double* Stabilization::fit_weights(Offset k, double* out) const {
  const double* g = OperatorAccess::weights(*fit_, k, out);
  if (nb_ == dim_) return g;
  if (g != out) std::copy(g, g + dim_, out);
  for (int q = 0; q < nb_ - dim_; ++q) out[dim_ + q] = OperatorAccess::weight(*fit_, k, q, Derivative::hessian);
  return out;
}

const double* Stabilization::fit_diagonal(std::size_t i, double* out) const {
  const double* g = OperatorAccess::diagonal(*fit_, i);
  if (nb_ == dim_) return g;
  std::copy(g, g + dim_, out);
  const double* h = OperatorAccess::diagonal(*fit_, i, Derivative::hessian);
  std::copy(h, h + (nb_ - dim_), out + dim_);
  return out;
}

void Stabilization::basis_of(std::size_t i, std::size_t j, double* p) const {
  const int d = dim_, nb = nb_;
  const double* xi = x_.data() + i * d;
  const double* xj = x_.data() + j * d;
  if (d == 2) nb == 2 ? basis<2, 2>(xi, xj, p) : basis<2, 5>(xi, xj, p);
  else nb == 3 ? basis<3, 3>(xi, xj, p) : basis<3, 9>(xi, xj, p);
}

template <class Add>
void Stabilization::centre_row(std::size_t r, Add&& add) const {
  // Row r of the block of centre r: A_r = -sum_k a_rk, a_rk = w_rk V_k p_rk.
  if (!(cv_[r] > 0.0)) return;
  const int nb = nb_;
  const BondGraph& g = fit_->graph();
  double p[9], weights[9], diagonal[9];
  const double scale = cv_[r];
  double s[9] = {}, wsum = 0.0;
  for (Offset k = g.begin(r); k < g.end(r); ++k) {
    basis_of(r, g.col(k), p);
    for (int q = 0; q < nb; ++q) s[q] -= wv_[k] * p[q];
    wsum += wv_[k];
  }
  // The family first, then r itself: a model that folds columns together (the plate's
  // ghosts onto their images) sums them in this order.
  for (Offset k = g.begin(r); k < g.end(r); ++k)
    if (g.alive(k)) add(g.col(k), scale * (-wv_[k] - dot(s, fit_weights(k, weights), nb)));
  add(static_cast<ParticleId>(r), scale * (wsum - dot(s, fit_diagonal(r, diagonal), nb)));
}

template <class Add>
void Stabilization::member_row(std::size_t i, std::size_t r, double wv_ir, Add&& add) const {
  // Row r of the block of a centre i whose family holds r (a live bond): with c = cv_i w_ir V_r,
  // c (e_r - e_i - sum_k (p_ir . a_ik) (e_k - e_i)).
  if (!(cv_[i] > 0.0)) return;
  const int d = dim_, nb = nb_;
  const BondGraph& g = fit_->graph();
  double p[9], weights[9], diagonal[9];
  const double c = cv_[i] * wv_ir;
  basis_of(i, r, p);
  add(static_cast<ParticleId>(r), c);
  if (nb == d) {
    // The same entries with w_ir V_r applied to p_ir before the dot products: the rounding
    // the first-order rows had before the two orders shared this code, kept so that no
    // first-order answer moved with the merge (ADR's iteration count follows 1e-14 changes).
    double a[3];
    for (int q = 0; q < d; ++q) a[q] = wv_ir * p[q];
    add(static_cast<ParticleId>(i), cv_[i] * (-wv_ir - dot(a, fit_diagonal(i, diagonal), d)));
    for (Offset k = g.begin(i); k < g.end(i); ++k)
      if (g.alive(k)) add(g.col(k), -cv_[i] * dot(a, fit_weights(k, weights), d));
    return;
  }
  add(static_cast<ParticleId>(i), -c * (1.0 + dot(p, fit_diagonal(i, diagonal), nb)));
  for (Offset k = g.begin(i); k < g.end(i); ++k)
    if (g.alive(k)) add(g.col(k), -c * dot(p, fit_weights(k, weights), nb));
}

template <class Add>
void Stabilization::row(std::size_t r, Add&& add) const {
  const BondGraph& g = fit_->graph();
  centre_row(r, add);
  for (Offset t = g.dual_begin(r); t < g.dual_end(r); ++t)
    if (g.dual_alive(t)) member_row(g.dual_col(t), r, t_wv_[t], add);
}

void Stabilization::add_blocks(ScalarCsr& S0, const std::vector<ParticleId>& centres, double sign) const {
  // Block m couples Q = {m} + H_m: gathered densely (|Q|^2 values), then added row by row
  // with one walk along each stored row of Q.
  const BondGraph& g = fit_->graph();
  std::vector<int> local(S0.rows(), -1);  // column -> its place in Q
  std::vector<ParticleId> Q;
  std::vector<double> B;
  for (const ParticleId m : centres) {
    Q.assign(1, m);
    for (Offset k = g.begin(m); k < g.end(m); ++k) Q.push_back(g.col(k));
    const std::size_t q = Q.size();
    for (std::size_t a = 0; a < q; ++a) local[Q[a]] = static_cast<int>(a);
    B.assign(q * q, 0.0);
    auto into = [&](std::size_t row) {
      return [&, row](ParticleId j, double v) { B[row * q + static_cast<std::size_t>(local[j])] += v; };
    };
    centre_row(m, into(0));
    for (Offset k = g.begin(m); k < g.end(m); ++k)
      if (g.alive(k)) member_row(m, g.col(k), wv_[k], into(static_cast<std::size_t>(k - g.begin(m)) + 1));
    for (std::size_t a = 0; a < q; ++a) {
      std::size_t found = 0, nonzero = 0;
      for (std::size_t b = 0; b < q; ++b) nonzero += B[a * q + b] != 0.0;
      for (Offset e = S0.offsets[Q[a]]; e < S0.offsets[Q[a] + 1]; ++e) {
        const int b = local[S0.cols[e]];
        if (b < 0) continue;
        S0.values[e] += sign * B[a * q + static_cast<std::size_t>(b)];
        found += B[a * q + static_cast<std::size_t>(b)] != 0.0;
      }
      if (found != nonzero)
        throw std::logic_error("Stabilization::add_blocks: a block has an entry outside the stored pattern");
    }
    for (const ParticleId j : Q) local[j] = -1;
  }
}

void Stabilization::add_row(std::size_t i, RowAccumulator& acc, int copies) const {
  row(i, [&acc, copies](ParticleId j, double v) {
    double* block = acc.at(j);
    for (int k = 0; k < copies; ++k) block[k * (copies + 1)] += v;
  });
}

void Stabilization::add_row(std::size_t i, const std::function<void(ParticleId, double)>& add) const { row(i, add); }

std::size_t Stabilization::memory_bytes() const {
  return (x_.size() + cv_.size() + c0_.size() + factor_.size() + wv_.size() + t_wv_.size() + r_.size()) * sizeof(double);
}

StabilizationScale shape_scale(const NonlocalOperator& G, double modulus, std::vector<double> volume) {
  return [&G, modulus, volume = std::move(volume)](std::size_t i) {
    const int d = G.dim();
    double tr = 0.0;
    for (int a = 0; a < d; ++a) tr += G.shape(i)[a * d + a];
    return G.is_detached(i) || !(tr > 0.0) ? 0.0 : modulus / tr * volume[i];
  };
}

StabilizationScale bending_scale(const NonlocalOperator& op, double c_hg, double rigidity, std::vector<double> area) {
  return [&op, c_hg, rigidity, area = std::move(area)](std::size_t i) {
    if (!(area[i] > 0.0) || !(c_hg > 0.0) || op.is_detached(i)) return 0.0;
    const int d = op.dim();
    const std::vector<double>& wv = OperatorAccess::wv(op);
    const std::vector<double>& x = OperatorAccess::positions(op);
    double q = 0.0;
    op.graph().for_each_live(i, [&](Offset k, ParticleId j) {
      double r2 = 0.0;
      for (int a = 0; a < d; ++a) {
        const double e = x[static_cast<std::size_t>(j) * d + a] - x[i * d + a];
        r2 += e * e;
      }
      q += wv[k] * r2 * r2 / 4.0;
    });
    return c_hg * rigidity * area[i] / q;
  };
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

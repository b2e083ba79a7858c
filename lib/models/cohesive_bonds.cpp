#include "perinom/models/cohesive_bonds.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace perinom {

namespace {
constexpr double pi = 3.14159265358979323846;
/// The mean of |cos| between a direction and a plane's normal: 1/2 in 3-D, 2/pi in 2-D.
double mean_crossing(int dim) { return dim == 3 ? 0.5 : 2.0 / pi; }
}  // namespace

double least_fracture_energy(int dim, const CohesiveLaw& law, double longest) {
  return dim * mean_crossing(dim) * law.f_t * law.f_t * longest / (2.0 * law.E);
}

CohesiveBonds::CohesiveBonds(int dim, const std::vector<double>& x, const std::vector<double>& volume,
                             const BondGraph& graph, const CohesiveLaw& law)
    : dim_(dim), x_(x), volume_(volume), S_(volume.size(), 0.0), law_(law) {
  if (!(law.f_t > 0.0) || !(law.G_f > 0.0) || !(law.E > 0.0))
    throw std::invalid_argument("CohesiveBonds: f_t, G_f and E must be positive");
  if (dim != 2 && dim != 3) throw std::invalid_argument("CohesiveBonds: dimension 2 or 3");
  eta_u_ = 2.0 * law.G_f / (dim * mean_crossing(dim) * law.f_t);
  double longest = 0.0;
  for (std::size_t i = 0; i < graph.rows(); ++i)
    graph.for_each_live(i, [&](Offset, ParticleId j) {
      double r2 = 0.0;
      for (int a = 0; a < dim; ++a) r2 += (x[j * dim + a] - x[i * dim + a]) * (x[j * dim + a] - x[i * dim + a]);
      S_[i] += volume[j] * std::sqrt(r2);
      longest = std::max(longest, std::sqrt(r2));
    });
  if (!(law.G_f > least_fracture_energy(dim, law, longest)))
    throw std::invalid_argument("CohesiveBonds: G_f is below the least for the longest bond (no softening branch)");
}

bool CohesiveBonds::at_peak(ParticleId i, ParticleId j, const double* u) const {
  double r2 = 0.0, eta = 0.0;  // eta |xi|, against eta_e |xi| = |xi|^2 f_t / E
  for (int a = 0; a < dim_; ++a) {
    const double xi = x_[j * dim_ + a] - x_[i * dim_ + a];
    r2 += xi * xi, eta += xi * (u[j * dim_ + a] - u[i * dim_ + a]);
  }
  return eta * law_.E >= r2 * law_.f_t;
}

void CohesiveBonds::add(const std::vector<std::pair<ParticleId, ParticleId>>& pairs) {
  for (const auto& [i, j] : pairs) {
    if (i == j || i < 0 || j < 0 || std::size_t(i) >= volume_.size() || std::size_t(j) >= volume_.size())
      throw std::invalid_argument("CohesiveBonds::add: a pair is not two particles of the cloud");
    Bond b{i, j, {0.0, 0.0, 0.0}, 0.0, 0.0, 0.0};
    double r2 = 0.0;
    for (int a = 0; a < dim_; ++a) {
      b.e[a] = x_[j * dim_ + a] - x_[i * dim_ + a];
      r2 += b.e[a] * b.e[a];
    }
    const double r = std::sqrt(r2);
    for (int a = 0; a < dim_; ++a) b.e[a] /= r;
    const double S = 0.5 * (S_[i] + S_[j]);
    if (!(S > 0.0)) throw std::invalid_argument("CohesiveBonds::add: a pair of particles without a family");
    b.F0 = volume_[i] * volume_[j] * 2.0 * dim_ * law_.f_t / S;
    b.eta_e = r * law_.f_t / law_.E;
    bonds_.push_back(b);
  }
  // The bonds of each particle, for tangent_row.
  at_ptr_.assign(volume_.size() + 1, 0);
  for (const Bond& b : bonds_) ++at_ptr_[b.i + 1], ++at_ptr_[b.j + 1];
  for (std::size_t i = 0; i < volume_.size(); ++i) at_ptr_[i + 1] += at_ptr_[i];
  at_bond_.assign(at_ptr_.back(), 0);
  std::vector<std::size_t> next(at_ptr_.begin(), at_ptr_.end() - 1);
  for (std::size_t k = 0; k < bonds_.size(); ++k) at_bond_[next[bonds_[k].i]++] = k, at_bond_[next[bonds_[k].j]++] = k;
  slope_.assign(bonds_.size(), 0.0);
}

double CohesiveBonds::opening(const Bond& b, const double* u) const {
  double eta = 0.0;
  for (int a = 0; a < dim_; ++a) eta += b.e[a] * (u[b.j * dim_ + a] - u[b.i * dim_ + a]);
  return eta;
}

double CohesiveBonds::envelope(const Bond& b, double kappa) const {
  if (kappa <= b.eta_e) return b.F0 * kappa / b.eta_e;
  if (kappa >= eta_u_) return 0.0;
  return b.F0 * (eta_u_ - kappa) / (eta_u_ - b.eta_e);
}

double CohesiveBonds::force(const Bond& b, double eta) const {
  if (eta <= 0.0) return b.F0 * eta / b.eta_e;  // closed: the faces in contact
  if (eta >= b.kappa) return envelope(b, eta);
  return envelope(b, b.kappa) * eta / b.kappa;  // unloading to the origin
}

double CohesiveBonds::add_force(const double* u, double* f, std::size_t first) const {
  double stored = 0.0;
  for (std::size_t k = first; k < bonds_.size(); ++k) {
    const Bond& b = bonds_[k];
    const double eta = opening(b, u), F = force(b, eta);
    if (F == 0.0) continue;
    for (int a = 0; a < dim_; ++a) f[b.j * dim_ + a] += F * b.e[a], f[b.i * dim_ + a] -= F * b.e[a];
    stored += 0.5 * F * eta;
  }
  return stored;
}

double CohesiveBonds::energy(const double* u) const {
  double w = 0.0;
  for (const Bond& b : bonds_) {
    const double eta = opening(b, u);
    w += 0.5 * force(b, eta) * eta;  // (closed: the contact's, elastic)
  }
  return w;
}

void CohesiveBonds::prepare_tangent(const double* u) {
  slope_.assign(bonds_.size(), 0.0);
  for (std::size_t k = 0; k < bonds_.size(); ++k) {
    const Bond& b = bonds_[k];
    const double eta = opening(b, u);
    if (eta <= 0.0) slope_[k] = b.F0 / b.eta_e;  // closed: the faces in contact
    else if (eta < b.kappa) slope_[k] = envelope(b, b.kappa) / b.kappa;  // the secant
    else if (eta < b.eta_e) slope_[k] = b.F0 / b.eta_e;
    else if (eta < eta_u_) slope_[k] = -b.F0 / (eta_u_ - b.eta_e);
  }
}

bool CohesiveBonds::touches(ParticleId i) const {
  return std::size_t(i) + 1 < at_ptr_.size() && at_ptr_[i + 1] > at_ptr_[i];
}

void CohesiveBonds::tangent_row(ParticleId i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks,
                                std::vector<ParticleId>& out_cols, std::vector<double>& out_blocks) const {
  const int d = dim_, d2 = d * d;
  out_cols = cols;
  if (touches(i)) {
    out_cols.push_back(i);
    for (std::size_t m = at_ptr_[i]; m < at_ptr_[i + 1]; ++m) {
      const Bond& b = bonds_[at_bond_[m]];
      out_cols.push_back(b.i == i ? b.j : b.i);
    }
  }
  std::sort(out_cols.begin(), out_cols.end());
  out_cols.erase(std::unique(out_cols.begin(), out_cols.end()), out_cols.end());
  out_blocks.assign(out_cols.size() * d2, 0.0);
  auto slot = [&](ParticleId j) { return std::size_t(std::lower_bound(out_cols.begin(), out_cols.end(), j) - out_cols.begin()); };
  for (std::size_t q = 0; q < cols.size(); ++q) {
    const std::size_t r = slot(cols[q]);
    for (int k = 0; k < d2; ++k) out_blocks[r * d2 + k] = blocks[q * d2 + k];
  }
  if (!touches(i)) return;
  for (std::size_t m = at_ptr_[i]; m < at_ptr_[i + 1]; ++m) {
    const Bond& b = bonds_[at_bond_[m]];
    const double k = slope_.empty() ? 0.0 : slope_[at_bond_[m]];
    const std::size_t ii = slot(i), jj = slot(b.i == i ? b.j : b.i);
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c) {
        const double kee = k * b.e[a] * b.e[c];
        out_blocks[(ii * d + a) * d + c] += kee;
        out_blocks[(jj * d + a) * d + c] -= kee;
      }
  }
}

void CohesiveBonds::commit(const double* u) {
  for (Bond& b : bonds_) b.kappa = std::max(b.kappa, opening(b, u));
}

void CohesiveBonds::add_row_sums(const std::vector<ParticleId>* rows, double* sums) const {
  const int d = dim_;
  auto add = [&](ParticleId p, const Bond& b) {
    std::size_t r = p;
    if (rows) {
      const auto at = std::lower_bound(rows->begin(), rows->end(), p);
      if (at == rows->end() || *at != p) return;
      r = std::size_t(at - rows->begin());
    }
    const double k = b.F0 / b.eta_e;
    // Row (p, a) of the pair's block k e e^T appears twice: at p's own column and at the other end's.
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c) sums[r * d + a] += 2.0 * k * std::abs(b.e[a] * b.e[c]);
  };
  for (const Bond& b : bonds_) add(b.i, b), add(b.j, b);
}

std::vector<double> CohesiveBonds::kappas() const {
  std::vector<double> k(bonds_.size());
  for (std::size_t b = 0; b < bonds_.size(); ++b) k[b] = bonds_[b].kappa;
  return k;
}

void CohesiveBonds::restore_kappas(const std::vector<double>& kappa) {
  if (kappa.size() != bonds_.size())
    throw std::invalid_argument("CohesiveBonds::restore_kappas: " + std::to_string(kappa.size()) + " openings for " +
                                std::to_string(bonds_.size()) + " softening bonds");
  for (const double k : kappa)
    if (!(k >= 0.0) || !std::isfinite(k)) throw std::invalid_argument("CohesiveBonds::restore_kappas: an opening is negative or not finite");
  for (std::size_t b = 0; b < bonds_.size(); ++b) bonds_[b].kappa = kappa[b];
}

std::size_t CohesiveBonds::spent() const {
  return std::size_t(std::count_if(bonds_.begin(), bonds_.end(), [&](const Bond& b) { return b.kappa >= eta_u_; }));
}

double CohesiveBonds::dissipated() const {
  double w = 0.0;
  for (const Bond& b : bonds_) {
    const double k = b.kappa;
    if (k <= b.eta_e) continue;
    // The envelope's area up to kappa, less what unloading from kappa gives back.
    const double Fk = envelope(b, k);
    const double area = 0.5 * b.F0 * b.eta_e + 0.5 * (b.F0 + Fk) * (std::min(k, eta_u_) - b.eta_e);
    w += area - 0.5 * Fk * k;
  }
  return w;
}

}  // namespace perinom

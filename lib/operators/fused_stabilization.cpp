#include "perinom/operators/fused_stabilization.hpp"

#include <algorithm>
#include <cstdint>

#include "operator_access.hpp"

namespace perinom {

FusedStabilization::FusedStabilization(const PointCloud& cloud, const NonlocalOperator& G, double modulus)
    : dim_(cloud.dim), modulus_(modulus), G_(&G), cvK_(cloud.size() * cloud.dim * cloud.dim),
      cv_(cloud.size()), volume_(cloud.volume) {
  const std::size_t n = cloud.size();
  for (std::size_t i = 0; i < n; ++i) refresh_particle(i);
  if (G.precision() == WeightPrecision::float32) c32_.resize(G.bonds());
  else c_.resize(G.bonds());
  const BondGraph& g = G.graph();
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t l = 0; l < n; ++l)
    for (Offset k = g.begin(l); k < g.end(l); ++k) refresh_bond(k, l, g.col(k));
}

std::optional<FusedStabilization> FusedStabilization::make(const PointCloud& cloud, const NonlocalOperator& G,
                                                          double modulus) {
  if (!G.graph().symmetric()) return std::nullopt;
  return FusedStabilization(cloud, G, modulus);
}

void FusedStabilization::refresh_particle(std::size_t i) {
  const int d = dim_, d2 = d * d;
  double tr = 0.0;
  for (int a = 0; a < d; ++a) tr += G_->shape(i)[a * d + a];
  cv_[i] = G_->is_detached(i) || !(tr > 0.0) ? 0.0 : modulus_ / tr * volume_[i];
  for (int k = 0; k < d2; ++k) cvK_[i * d2 + k] = G_->shape(i)[k] * cv_[i];
}

void FusedStabilization::refresh_bond(Offset k, std::size_t l, std::size_t j) {
  // c_lj = cv_l wv_lj + cv_j wv_jl: bond (l, j) and its reverse (j, l), dead ones weigh 0.
  const BondGraph& g = G_->graph();
  const std::vector<double>& wv = OperatorAccess::wv(*G_);
  const Offset back = g.reverse(k);
  const double c = cv_[l] * (g.alive(k) ? wv[k] : 0.0) + cv_[j] * (g.alive(back) ? wv[back] : 0.0);
  if (c32_.empty()) c_[k] = c;
  else c32_[k] = float(c);
}

void FusedStabilization::refresh_rows(const std::vector<ParticleId>& rows_in) {
  const BondGraph& g = G_->graph();
  std::vector<ParticleId> rows = rows_in;
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  const bool parallel = rows.size() > 64;
#pragma omp parallel for schedule(static) if (parallel)
  for (std::size_t r = 0; r < rows.size(); ++r) refresh_particle(rows[r]);
  // Row i writes c of its bonds, and of their reverses (j, i) when row j is not refreshed
  // itself (then j writes it): each c has one writer.
  std::vector<std::uint8_t> listed(cv_.size(), 0);
  for (const ParticleId i : rows) listed[i] = 1;
#pragma omp parallel for schedule(dynamic, 16) if (parallel)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const ParticleId i = rows[r];
    for (Offset k = g.begin(i); k < g.end(i); ++k) {
      const ParticleId j = g.col(k);
      refresh_bond(k, i, j);
      if (!listed[j]) refresh_bond(g.reverse(k), j, i);
    }
  }
}

void FusedStabilization::gradient_and_laplacian(const double* u, double* H, double* lap) const {
  if (c32_.empty()) G_->apply_with_laplacian(u, c_.data(), H, lap);
  else G_->apply_with_laplacian(u, c32_.data(), H, lap);
}

void FusedStabilization::tensor_terms(const double* H, double* T) const {
  const int d = dim_, d2 = d * d;
  const std::size_t n = G_->gradient_rows();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const double* h = H + i * d2;
    const double* k = cvK_.data() + i * d2;
    double* t = T + i * d2;
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b) {
        double s = 0.0;
        for (int c = 0; c < d; ++c) s += h[a * d + c] * k[c * d + b];
        t[a * d + b] = s;
      }
  }
}

}  // namespace perinom

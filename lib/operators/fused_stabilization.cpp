#include "perinom/operators/fused_stabilization.hpp"

#include <algorithm>
#include <utility>

namespace perinom {
namespace {

// (partner, position) pairs of one row, sorted by partner.
void sorted_row(const ParticleId* partner, const Offset* position, Offset begin, Offset end,
                std::vector<std::pair<ParticleId, Offset>>& out) {
  out.clear();
  for (Offset k = begin; k < end; ++k) out.emplace_back(partner[k], position ? position[k] : k);
  std::sort(out.begin(), out.end());
}

}  // namespace

std::optional<FusedStabilization> FusedStabilization::make(const PointCloud& cloud,
                                                          const Families& families,
                                                          const BondWeights& weights,
                                                          GradientOperator& G,
                                                          const std::vector<double>& coefficient) {
  const DualSupport dual = dual_support(families);
  if (dual.offsets != families.offsets) return std::nullopt;
  const std::size_t n = cloud.size();
  const int d2 = cloud.dim * cloud.dim;
  std::vector<double> cv(n), cvK(weights.shape);
  for (std::size_t i = 0; i < n; ++i) {
    cv[i] = coefficient[i] * cloud.volume[i];
    for (int k = 0; k < d2; ++k) cvK[i * d2 + k] *= cv[i];
  }
  // c_lj = cv_l wv_lj + cv_j wv_jl: bond (l, j) meets its reverse (j, l) in l's dual row.
  std::vector<double> c(families.bonds());
  bool symmetric = true;
#pragma omp parallel
  {
    std::vector<std::pair<ParticleId, Offset>> row, drow;
#pragma omp for schedule(dynamic, 256) reduction(&& : symmetric)
    for (std::size_t l = 0; l < n; ++l) {
      sorted_row(families.neighbors.data(), nullptr, families.begin(l), families.end(l), row);
      sorted_row(dual.neighbors.data(), dual.bond.data(), dual.offsets[l], dual.offsets[l + 1], drow);
      for (std::size_t m = 0; m < row.size(); ++m) {
        const auto [j, k] = row[m];
        if (drow[m].first != j) {
          symmetric = false;
          break;
        }
        c[k] = cv[l] * weights.wv[k] + cv[j] * weights.wv[drow[m].second];
      }
    }
  }
  if (!symmetric) return std::nullopt;
  G.set_bond_scalars(c);
  return FusedStabilization(cloud.dim, std::move(cvK));
}

void FusedStabilization::tensor_terms(const double* H, double* T) const {
  const int d = dim_, d2 = d * d;
  const std::size_t n = cvK_.size() / d2;
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

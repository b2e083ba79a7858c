#include "perinom/operators/stabilization.hpp"

#include "perinom/operators/row_accumulator.hpp"

namespace perinom {
namespace {

double dot(const double* a, const double* b, int d) {
  double s = 0.0;
  for (int k = 0; k < d; ++k) s += a[k] * b[k];
  return s;
}

}  // namespace

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

ScalarCsr assemble_stabilization(const PointCloud& cloud, const Families& fam,
                                 const BondWeights& bw, const GradientOperator& G,
                                 const std::vector<double>& coefficient) {
  const int d = cloud.dim;
  const std::size_t n = cloud.size();
  const DualSupport dual = dual_support(fam);
  std::vector<std::vector<ParticleId>> row_cols(n);
  std::vector<std::vector<double>> row_vals(n);
#pragma omp parallel
  {
    RowAccumulator acc(n, 1);
#pragma omp for schedule(dynamic, 64)
    for (std::size_t r = 0; r < n; ++r) {
      const double* xr = cloud.point(r);
      // Row r of M_r (r is the centre): A_r = -sum_k a_rk.
      {
        const double scale = coefficient[r] * cloud.volume[r];
        double s[3] = {0, 0, 0}, wsum = 0.0;
        for (Offset k = fam.begin(r); k < fam.end(r); ++k) {
          const double* xj = cloud.point(fam.neighbors[k]);
          for (int a = 0; a < d; ++a) s[a] -= bw.wv[k] * (xj[a] - xr[a]);
          wsum += bw.wv[k];
        }
        *acc.at(static_cast<ParticleId>(r)) += scale * (wsum - dot(s, G.diagonal(r), d));
        for (Offset k = fam.begin(r); k < fam.end(r); ++k)
          *acc.at(fam.neighbors[k]) += scale * (-bw.wv[k] - dot(s, G.weight(k), d));
      }
      // Row r of M_i for every i whose family holds r: A_r = a_ir = w_ir V_r xi_ir.
      for (Offset t = dual.offsets[r]; t < dual.offsets[r + 1]; ++t) {
        const ParticleId i = dual.neighbors[t];
        const Offset p = dual.bond[t];
        const double scale = coefficient[i] * cloud.volume[i];
        const double* xi = cloud.point(i);
        double a[3] = {0, 0, 0};
        for (int c = 0; c < d; ++c) a[c] = bw.wv[p] * (xr[c] - xi[c]);
        *acc.at(static_cast<ParticleId>(r)) += scale * bw.wv[p];
        *acc.at(i) += scale * (-bw.wv[p] - dot(a, G.diagonal(i), d));
        for (Offset k = fam.begin(i); k < fam.end(i); ++k)
          *acc.at(fam.neighbors[k]) -= scale * dot(a, G.weight(k), d);
      }
      acc.finish();
      row_cols[r] = acc.cols();
      row_vals[r].resize(row_cols[r].size());
      for (std::size_t k = 0; k < row_cols[r].size(); ++k) row_vals[r][k] = *acc.block(k);
      acc.clear();
    }
  }
  ScalarCsr S;
  S.offsets.assign(n + 1, 0);
  for (std::size_t r = 0; r < n; ++r) S.offsets[r + 1] = S.offsets[r] + row_cols[r].size();
  S.cols.reserve(S.offsets.back());
  S.values.reserve(S.offsets.back());
  for (std::size_t r = 0; r < n; ++r) {
    S.cols.insert(S.cols.end(), row_cols[r].begin(), row_cols[r].end());
    S.values.insert(S.values.end(), row_vals[r].begin(), row_vals[r].end());
    std::vector<ParticleId>().swap(row_cols[r]);
    std::vector<double>().swap(row_vals[r]);
  }
  return S;
}

}  // namespace perinom

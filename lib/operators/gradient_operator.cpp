#include "perinom/operators/gradient_operator.hpp"

#include <stdexcept>

namespace perinom {
namespace {

// Compile-time sizes let the compiler keep the accumulators in registers.
template <int D, int NC>
void gather_gradient(std::size_t n, const Offset* off, const ParticleId* col, const double* w,
                     const double* f, double* out) {
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double acc[NC][D] = {};
    const double* fi = f + i * NC;
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const double* fj = f + static_cast<std::size_t>(col[k]) * NC;
      const double* g = w + k * D;
      for (int c = 0; c < NC; ++c) {
        const double diff = fj[c] - fi[c];
        for (int b = 0; b < D; ++b) acc[c][b] += diff * g[b];
      }
    }
    double* o = out + i * NC * D;
    for (int c = 0; c < NC; ++c)
      for (int b = 0; b < D; ++b) o[c * D + b] = acc[c][b];
  }
}

// Rows are all of 0..n-1, or the n ids in `rows`.
inline std::size_t row_of(const ParticleId* rows, std::size_t r) { return rows ? rows[r] : r; }

template <int D, int NC>
void gather_transpose(std::size_t n, const ParticleId* rows, const Offset* off,
                      const ParticleId* col, const double* w, const double* diag,
                      const double* q, double* out) {
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row_of(rows, r);
    double acc[NC] = {};
    const double* qi = q + i * NC * D;
    for (int c = 0; c < NC; ++c)
      for (int b = 0; b < D; ++b) acc[c] += diag[i * D + b] * qi[c * D + b];
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const double* qm = q + static_cast<std::size_t>(col[k]) * NC * D;
      const double* g = w + k * D;
      for (int c = 0; c < NC; ++c)
        for (int b = 0; b < D; ++b) acc[c] += g[b] * qm[c * D + b];
    }
    for (int c = 0; c < NC; ++c) out[i * NC + c] = acc[c];
  }
}

template <int D, int NC>
void gather_divergence(std::size_t n, const ParticleId* rows, const Offset* off,
                       const ParticleId* col, const double* w, const double* q, double* out) {
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row_of(rows, r);
    double acc[NC] = {};
    const double* qi = q + i * NC * D;
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const double* qj = q + static_cast<std::size_t>(col[k]) * NC * D;
      const double* g = w + k * D;
      for (int c = 0; c < NC; ++c)
        for (int b = 0; b < D; ++b) acc[c] += (qj[c * D + b] - qi[c * D + b]) * g[b];
    }
    for (int c = 0; c < NC; ++c) out[i * NC + c] = acc[c];
  }
}

[[noreturn]] void unsupported(int d, int nc) {
  throw std::invalid_argument("GradientOperator: no kernel for dimension " + std::to_string(d) +
                              " with " + std::to_string(nc) + " components");
}

}  // namespace

GradientOperator::GradientOperator(const PointCloud& cloud, const Families& families,
                                   const BondWeights& bw)
    : dim_(cloud.dim), offsets_(families.offsets), cols_(families.neighbors) {
  const int d = dim_;
  const std::size_t n = rows();
  w_.resize(bonds() * d);
  diag_.assign(n * d, 0.0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    const double* Kinv = bw.shape_inverse.data() + i * d * d;
    for (Offset k = offsets_[i]; k < offsets_[i + 1]; ++k) {
      const std::size_t j = cols_[k];
      for (int b = 0; b < d; ++b) {
        double g = 0.0;
        for (int c = 0; c < d; ++c) g += Kinv[b * d + c] * (cloud.x[j * d + c] - cloud.x[i * d + c]);
        w_[k * d + b] = bw.wv[k] * g;
        diag_[i * d + b] -= w_[k * d + b];
      }
    }
  }
  DualSupport dual = dual_support(families);
  t_offsets_ = std::move(dual.offsets);
  t_cols_ = std::move(dual.neighbors);
  t_w_.resize(bonds() * d);
  for (std::size_t s = 0; s < dual.bond.size(); ++s)
    for (int b = 0; b < d; ++b) t_w_[s * d + b] = w_[dual.bond[s] * d + b];
}

void GradientOperator::apply(const double* f, int nc, double* out) const {
  const std::size_t n = rows();
  const Offset* off = offsets_.data();
  const ParticleId* col = cols_.data();
  const double* w = w_.data();
  if (dim_ == 2 && nc == 1) return gather_gradient<2, 1>(n, off, col, w, f, out);
  if (dim_ == 2 && nc == 2) return gather_gradient<2, 2>(n, off, col, w, f, out);
  if (dim_ == 2 && nc == 4) return gather_gradient<2, 4>(n, off, col, w, f, out);
  if (dim_ == 3 && nc == 1) return gather_gradient<3, 1>(n, off, col, w, f, out);
  if (dim_ == 3 && nc == 3) return gather_gradient<3, 3>(n, off, col, w, f, out);
  if (dim_ == 3 && nc == 9) return gather_gradient<3, 9>(n, off, col, w, f, out);
  unsupported(dim_, nc);
}

void GradientOperator::apply_transpose(const double* q, int nc, double* out,
                                       const std::vector<ParticleId>* subset) const {
  const std::size_t n = subset ? subset->size() : rows();
  const ParticleId* r = subset ? subset->data() : nullptr;
  const Offset* off = t_offsets_.data();
  const ParticleId* col = t_cols_.data();
  const double* w = t_w_.data();
  const double* dg = diag_.data();
  if (dim_ == 2 && nc == 1) return gather_transpose<2, 1>(n, r, off, col, w, dg, q, out);
  if (dim_ == 2 && nc == 2) return gather_transpose<2, 2>(n, r, off, col, w, dg, q, out);
  if (dim_ == 3 && nc == 1) return gather_transpose<3, 1>(n, r, off, col, w, dg, q, out);
  if (dim_ == 3 && nc == 3) return gather_transpose<3, 3>(n, r, off, col, w, dg, q, out);
  unsupported(dim_, nc);
}

void GradientOperator::divergence(const double* q, int nc, double* out,
                                  const std::vector<ParticleId>* subset) const {
  const std::size_t n = subset ? subset->size() : rows();
  const ParticleId* r = subset ? subset->data() : nullptr;
  const Offset* off = offsets_.data();
  const ParticleId* col = cols_.data();
  const double* w = w_.data();
  if (dim_ == 2 && nc == 1) return gather_divergence<2, 1>(n, r, off, col, w, q, out);
  if (dim_ == 2 && nc == 2) return gather_divergence<2, 2>(n, r, off, col, w, q, out);
  if (dim_ == 3 && nc == 1) return gather_divergence<3, 1>(n, r, off, col, w, q, out);
  if (dim_ == 3 && nc == 3) return gather_divergence<3, 3>(n, r, off, col, w, q, out);
  unsupported(dim_, nc);
}

std::size_t GradientOperator::memory_bytes() const {
  return (offsets_.size() + t_offsets_.size()) * sizeof(Offset) +
         (cols_.size() + t_cols_.size()) * sizeof(ParticleId) +
         (w_.size() + t_w_.size() + diag_.size()) * sizeof(double);
}

}  // namespace perinom

#include "perinom/operators/gradient_operator.hpp"

#include <stdexcept>
#include <string>

#include "gather_kernels.hpp"

namespace perinom {
namespace {

[[noreturn]] void unsupported(int d, int nc) {
  throw std::invalid_argument("GradientOperator: no kernel for dimension " + std::to_string(d) +
                              " with " + std::to_string(nc) + " components");
}

}  // namespace

GradientOperator::GradientOperator(const PointCloud& cloud, const Families& families,
                                   const BondWeights& bw, WeightPrecision precision)
    : dim_(cloud.dim), precision_(precision), offsets_(families.offsets), cols_(families.neighbors) {
  const bool single = precision == WeightPrecision::float32;
  const int d = dim_;
  const std::size_t n = rows();
  w_.resize(bonds() * d);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    const double* Kinv = bw.shape_inverse.data() + i * d * d;
    for (Offset k = offsets_[i]; k < offsets_[i + 1]; ++k) {
      const std::size_t j = cols_[k];
      for (int b = 0; b < d; ++b) {
        double g = 0.0;
        for (int c = 0; c < d; ++c) g += Kinv[b * d + c] * (cloud.x[j * d + c] - cloud.x[i * d + c]);
        w_[k * d + b] = single ? double(float(bw.wv[k] * g)) : bw.wv[k] * g;
      }
    }
  }
  finish(families);
}

GradientOperator::GradientOperator(const Families& families, int dim, std::vector<double> g,
                                   WeightPrecision precision)
    : dim_(dim), precision_(precision), offsets_(families.offsets), cols_(families.neighbors), w_(std::move(g)) {
  if (w_.size() != bonds() * dim)
    throw std::invalid_argument("GradientOperator: " + std::to_string(w_.size()) + " weights for " +
                                std::to_string(bonds()) + " bonds in " + std::to_string(dim) + "-D");
  if (precision == WeightPrecision::float32)
    for (double& v : w_) v = double(float(v));
  finish(families);
}

void GradientOperator::finish(const Families& families) {
  const int d = dim_;
  const std::size_t n = rows();
  // The diagonal sums the weights as stored, so G of a constant is zero either way.
  diag_.assign(n * d, 0.0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i)
    for (Offset k = offsets_[i]; k < offsets_[i + 1]; ++k)
      for (int b = 0; b < d; ++b) diag_[i * d + b] -= w_[k * d + b];
  DualSupport dual = dual_support(families);
  t_offsets_ = std::move(dual.offsets);
  t_cols_ = std::move(dual.neighbors);
  t_w_.resize(bonds() * d);
  for (std::size_t s = 0; s < dual.bond.size(); ++s)
    for (int b = 0; b < d; ++b) t_w_[s * d + b] = w_[dual.bond[s] * d + b];
  if (precision_ == WeightPrecision::float32) {
    w32_.assign(w_.begin(), w_.end());
    t_w32_.assign(t_w_.begin(), t_w_.end());
    std::vector<double>().swap(w_);
    std::vector<double>().swap(t_w_);
  }
}

namespace {

template <class W>
void apply_with(int d, std::size_t n, const Offset* off, const ParticleId* col, const W* w,
                const double* f, int nc, double* out) {
  namespace k = kernels;
  if (d == 2 && nc == 1) return k::gradient<2, 1>(n, off, col, w, f, out);
  if (d == 2 && nc == 2) return k::gradient2(n, off, col, w, f, out);
  if (d == 2 && nc == 4) return k::gradient<2, 4>(n, off, col, w, f, out);
  if (d == 2 && nc == 9) return k::gradient<2, 9>(n, off, col, w, f, out);  // 3 x 3 stresses in 2-D
  if (d == 3 && nc == 1) return k::gradient<3, 1>(n, off, col, w, f, out);
  if (d == 3 && nc == 3) return k::gradient3(n, off, col, w, f, out);
  if (d == 3 && nc == 9) return k::gradient<3, 9>(n, off, col, w, f, out);
  unsupported(d, nc);
}

template <class W>
void transpose_with(int d, std::size_t n, const ParticleId* r, const Offset* off,
                    const ParticleId* col, const W* w, const double* dg, const double* q, int nc,
                    double* out) {
  namespace k = kernels;
  if (d == 2 && nc == 1) return k::transpose<2, 1>(n, r, off, col, w, dg, q, out);
  if (d == 2 && nc == 2) return k::transpose2(n, r, off, col, w, dg, q, out);
  if (d == 3 && nc == 1) return k::transpose<3, 1>(n, r, off, col, w, dg, q, out);
  if (d == 3 && nc == 3) return k::transpose3(n, r, off, col, w, dg, q, out);
  unsupported(d, nc);
}

template <class W>
void divergence_with(int d, std::size_t n, const ParticleId* r, const Offset* off,
                     const ParticleId* col, const W* w, const double* q, int nc, double* out) {
  namespace k = kernels;
  if (d == 2 && nc == 1) return k::divergence<2, 1>(n, r, off, col, w, q, out);
  if (d == 2 && nc == 2) return k::divergence<2, 2>(n, r, off, col, w, q, out);
  if (d == 3 && nc == 1) return k::divergence<3, 1>(n, r, off, col, w, q, out);
  if (d == 3 && nc == 3) return k::divergence<3, 3>(n, r, off, col, w, q, out);
  unsupported(d, nc);
}

}  // namespace

void GradientOperator::apply(const double* f, int nc, double* out) const {
  const Offset* off = offsets_.data();
  const ParticleId* col = cols_.data();
  if (!w32_.empty()) return apply_with(dim_, rows(), off, col, w32_.data(), f, nc, out);
  apply_with(dim_, rows(), off, col, w_.data(), f, nc, out);
}

void GradientOperator::apply_transpose(const double* q, int nc, double* out,
                                       const std::vector<ParticleId>* subset) const {
  const std::size_t n = subset ? subset->size() : rows();
  const ParticleId* r = subset ? subset->data() : nullptr;
  const Offset* off = t_offsets_.data();
  const ParticleId* col = t_cols_.data();
  if (!t_w32_.empty()) return transpose_with(dim_, n, r, off, col, t_w32_.data(), diag_.data(), q, nc, out);
  transpose_with(dim_, n, r, off, col, t_w_.data(), diag_.data(), q, nc, out);
}

void GradientOperator::divergence(const double* q, int nc, double* out,
                                  const std::vector<ParticleId>* subset) const {
  const std::size_t n = subset ? subset->size() : rows();
  const ParticleId* r = subset ? subset->data() : nullptr;
  const Offset* off = offsets_.data();
  const ParticleId* col = cols_.data();
  if (!w32_.empty()) return divergence_with(dim_, n, r, off, col, w32_.data(), q, nc, out);
  divergence_with(dim_, n, r, off, col, w_.data(), q, nc, out);
}

void GradientOperator::set_bond_scalars(const std::vector<double>& c) {
  if (c.size() != bonds()) throw std::invalid_argument("GradientOperator: one bond scalar per bond expected");
  std::vector<double>().swap(c_);
  std::vector<float>().swap(c32_);
  if (precision_ == WeightPrecision::float32) c32_.assign(c.begin(), c.end());
  else c_ = c;
}

void GradientOperator::apply_with_laplacian(const double* f, double* out, double* lap) const {
  if (!has_bond_scalars()) throw std::logic_error("GradientOperator: apply_with_laplacian without bond scalars");
  namespace k = kernels;
  const std::size_t n = rows();
  const Offset* off = offsets_.data();
  const ParticleId* col = cols_.data();
  const bool single = !w32_.empty();
  if (dim_ == 2 && single) return k::gradient2<float, true>(n, off, col, w32_.data(), f, out, c32_.data(), lap);
  if (dim_ == 2) return k::gradient2<double, true>(n, off, col, w_.data(), f, out, c_.data(), lap);
  if (single) return k::gradient3<float, true>(n, off, col, w32_.data(), f, out, c32_.data(), lap);
  k::gradient3<double, true>(n, off, col, w_.data(), f, out, c_.data(), lap);
}

std::size_t GradientOperator::memory_bytes() const {
  return (offsets_.size() + t_offsets_.size()) * sizeof(Offset) +
         (cols_.size() + t_cols_.size()) * sizeof(ParticleId) +
         (w_.size() + t_w_.size() + diag_.size() + c_.size()) * sizeof(double) +
         (w32_.size() + t_w32_.size() + c32_.size()) * sizeof(float);
}

}  // namespace perinom

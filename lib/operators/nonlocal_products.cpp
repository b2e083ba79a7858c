// The products of NonlocalOperator and its first-order row fit. They live apart from the
// assembly so that they are compiled for this machine's processor (PERINOM_NATIVE) while the
// code that uses Eigen is not (lib/CMakeLists.txt says why).
#include <stdexcept>
#include <string>
#include <type_traits>

#include "gather_kernels.hpp"
#include "perinom/operators/nonlocal_operator.hpp"

namespace perinom {

bool NonlocalOperator::fit_first_order(std::size_t i, const double* Kinv) {
  const int d = dim_;
  const bool single = precision_ == WeightPrecision::float32;
  const BondGraph& graph = *graph_;
  const double* x = x_.data();
  for (Offset k = graph.begin(i); k < graph.end(i); ++k) {
    const std::size_t j = graph.col(k);
    const Offset t = graph.dual_entry(k);
    if (!graph.alive(k)) {
      for (int b = 0; b < d; ++b) grad_.set(k, t, b, 0.0);
      continue;
    }
    for (int b = 0; b < d; ++b) {
      double g = 0.0;
      for (int c = 0; c < d; ++c) g += Kinv[b * d + c] * (x[j * d + c] - x[i * d + c]);
      grad_.set(k, t, b, single ? double(float(wv_[k] * g)) : wv_[k] * g);
    }
  }
  finish_row(i);
  return true;
}

namespace {

template <int V>
using Int = std::integral_constant<int, V>;

[[noreturn]] void unsupported(int m) {
  throw std::invalid_argument("NonlocalOperator: no kernel for " + std::to_string(m) + " weights per bond");
}

// Calls run(Int<M>) for the weights per bond m: the kernels are templates on it.
template <class Run>
void with_m(int m, Run&& run) {
  if (m == 2) return run(Int<2>{});
  if (m == 3) return run(Int<3>{});
  if (m == 6) return run(Int<6>{});
  unsupported(m);
}

// Calls run(Int<NC>) for the common component counts, and returns false for the others
// (served by the *_any kernels).
template <class Run>
bool with_nc(int nc, Run&& run) {
  if (nc == 1) return run(Int<1>{}), true;
  if (nc == 2) return run(Int<2>{}), true;
  if (nc == 3) return run(Int<3>{}), true;
  return false;
}

std::size_t stride_of(const FieldLayout& l) { return static_cast<std::size_t>(l.stride > 0 ? l.stride : l.components); }

template <class W>
void apply_with(int m, std::size_t n, const Offset* off, const ParticleId* col, const W* w, const double* f,
                FieldLayout layout, double* out) {
  namespace k = kernels;
  const int nc = layout.components;
  const std::size_t stride = stride_of(layout);
  if (stride == static_cast<std::size_t>(nc)) {  // the point-major hot cases
    if (m == 3 && nc == 3) return k::gradient3(n, off, col, w, f, out);
    if (m == 2 && nc == 2) return k::gradient2(n, off, col, w, f, out);
    if (m == 2 && nc == 4) return k::gradient<2, 4>(n, off, col, w, f, out);
    if (m == 2 && nc == 9) return k::gradient<2, 9>(n, off, col, w, f, out);  // 3 x 3 stresses in 2-D
    if (m == 3 && nc == 9) return k::gradient<3, 9>(n, off, col, w, f, out);
  }
  with_m(m, [&](auto M) {
    constexpr int MV = decltype(M)::value;
    if (!with_nc(nc, [&](auto NC) { k::gradient<MV, decltype(NC)::value>(n, off, col, w, f, out, stride); }))
      k::gradient_any<MV>(n, off, col, w, f, nc, stride, out);
  });
}

template <class W>
void transpose_with(int m, std::size_t n, const ParticleId* r, const Offset* off, const ParticleId* col, const W* w,
                    const double* dg, const double* q, FieldLayout layout, double* out) {
  namespace k = kernels;
  const int nc = layout.components;
  const std::size_t stride = stride_of(layout);
  if (stride == static_cast<std::size_t>(nc)) {
    if (m == 3 && nc == 3) return k::transpose3(n, r, off, col, w, dg, q, out);
    if (m == 2 && nc == 2) return k::transpose2(n, r, off, col, w, dg, q, out);
  }
  with_m(m, [&](auto M) {
    constexpr int MV = decltype(M)::value;
    if (!with_nc(nc, [&](auto NC) { k::transpose<MV, decltype(NC)::value>(n, r, off, col, w, dg, q, out, stride); }))
      k::transpose_any<MV>(n, r, off, col, w, dg, q, nc, stride, out);
  });
}

template <class W>
void divergence_with(int m, std::size_t n, const ParticleId* r, const Offset* off, const ParticleId* col,
                     const W* w, const double* q, FieldLayout layout, double* out) {
  namespace k = kernels;
  const int nc = layout.components;
  const std::size_t stride = stride_of(layout);
  with_m(m, [&](auto M) {
    constexpr int MV = decltype(M)::value;
    if (!with_nc(nc, [&](auto NC) { k::divergence<MV, decltype(NC)::value>(n, r, off, col, w, q, out, stride); }))
      k::divergence_any<MV>(n, r, off, col, w, q, nc, stride, out);
  });
}

void require(bool assembled) {
  if (!assembled)
    throw std::logic_error("NonlocalOperator: the Hessian weights were not assembled (OperatorOptions::hessian "
                           "is false, or the order is 1)");
}

}  // namespace

void NonlocalOperator::apply(const double* f, FieldLayout layout, double* out, Derivative which) const {
  const Block& b = block(which);
  require(b.m > 0);
  const Offset* off = graph_->offsets().data();
  const ParticleId* col = graph_->cols().data();
  if (!b.w32.empty()) return apply_with(b.m, gradient_rows(), off, col, b.w32.data(), f, layout, out);
  apply_with(b.m, gradient_rows(), off, col, b.w.data(), f, layout, out);
}

void NonlocalOperator::apply_transpose(const double* q, FieldLayout layout, double* out,
                                       const std::vector<ParticleId>* subset, Derivative which) const {
  const Block& b = block(which);
  require(b.m > 0);
  const std::size_t n = subset ? subset->size() : transpose_rows();
  const ParticleId* r = subset ? subset->data() : nullptr;
  const Offset* off = graph_->dual_offsets().data();
  const ParticleId* col = graph_->dual_cols().data();
  if (!b.t_w32.empty()) return transpose_with(b.m, n, r, off, col, b.t_w32.data(), b.diag.data(), q, layout, out);
  transpose_with(b.m, n, r, off, col, b.t_w.data(), b.diag.data(), q, layout, out);
}

void NonlocalOperator::divergence(const double* q, FieldLayout layout, double* out,
                                  const std::vector<ParticleId>* subset) const {
  const std::size_t n = subset ? subset->size() : transpose_rows();
  const ParticleId* r = subset ? subset->data() : nullptr;
  const Offset* off = graph_->offsets().data();
  const ParticleId* col = graph_->cols().data();
  if (!grad_.w32.empty()) return divergence_with(grad_.m, n, r, off, col, grad_.w32.data(), q, layout, out);
  divergence_with(grad_.m, n, r, off, col, grad_.w.data(), q, layout, out);
}

void NonlocalOperator::apply_with_laplacian(const double* f, const double* c, double* out, double* lap) const {
  if (!grad_.w32.empty())
    throw std::invalid_argument("NonlocalOperator::apply_with_laplacian: float32 weights take float bond scalars");
  namespace k = kernels;
  const Offset* off = graph_->offsets().data();
  const ParticleId* col = graph_->cols().data();
  if (dim_ == 2) return k::gradient2<double, true>(gradient_rows(), off, col, grad_.w.data(), f, out, c, lap);
  k::gradient3<double, true>(gradient_rows(), off, col, grad_.w.data(), f, out, c, lap);
}

void NonlocalOperator::apply_with_laplacian(const double* f, const float* c, double* out, double* lap) const {
  if (grad_.w32.empty())
    throw std::invalid_argument("NonlocalOperator::apply_with_laplacian: float64 weights take double bond scalars");
  namespace k = kernels;
  const Offset* off = graph_->offsets().data();
  const ParticleId* col = graph_->cols().data();
  if (dim_ == 2) return k::gradient2<float, true>(gradient_rows(), off, col, grad_.w32.data(), f, out, c, lap);
  k::gradient3<float, true>(gradient_rows(), off, col, grad_.w32.data(), f, out, c, lap);
}

}  // namespace perinom

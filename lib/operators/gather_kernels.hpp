#pragma once
// The row kernels of the nonlocal operator's products (internal to lib/operators).
// Every product is a gather: row i is summed by one thread in a fixed order, so results
// do not depend on the thread count. W is the stored weight type (double, or float for
// the single-precision weight option); the arithmetic is always double.
//
// The hot case, nc = d (the displacement gradient and the internal force), has kernels on
// short vectors (GCC/Clang vector extensions: 4 doubles in 3-D with a zero fourth lane, 2
// in 2-D), so one bond costs three (two) vector multiply-adds instead of nine (four) scalar
// ones. The templated kernels serve the other common counts (M weights per bond, NC
// components, a field stride), and the *_any kernels any count at all (one pass over the
// row per component).
#include <cstddef>

#include "perinom/core/types.hpp"

namespace perinom::kernels {

typedef double v2 __attribute__((vector_size(16)));
typedef double v4 __attribute__((vector_size(32)));

// Rows are all of 0..n-1, or the n ids in `rows`.
inline std::size_t row_of(const ParticleId* rows, std::size_t r) { return rows ? rows[r] : r; }

inline v4 load3(const double* p) { return v4{p[0], p[1], p[2], 0.0}; }
template <class W>
inline v4 load3(const W* p) { return v4{double(p[0]), double(p[1]), double(p[2]), 0.0}; }

/// out[(i*NC + c)*D + b] = sum_j (f_j[c] - f_i[c]) g_ij[b], f_i[c] = f[i*stride + c].
template <int D, int NC, class W>
void gradient(std::size_t n, const Offset* off, const ParticleId* col, const W* w, const double* f,
              double* out, std::size_t stride = NC) {
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double acc[NC][D] = {};
    const double* fi = f + i * stride;
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const double* fj = f + static_cast<std::size_t>(col[k]) * stride;
      const W* g = w + k * D;
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

/// gradient<3, 3>: the accumulators are the three columns of grad f. With Laplacian, also
/// lap[i*3 + c] = sum_j cw_ij (f_j - f_i)[c] from the same differences (cw: one scalar per
/// bond); without, cw and lap are not read.
template <class W, bool Laplacian = false>
void gradient3(std::size_t n, const Offset* off, const ParticleId* col, const W* w, const double* f,
               double* out, const W* cw = nullptr, double* lap = nullptr) {
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    v4 a0 = {}, a1 = {}, a2 = {}, l = {};
    const v4 fi = load3(f + i * 3);
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const v4 diff = load3(f + static_cast<std::size_t>(col[k]) * 3) - fi;
      const W* g = w + k * 3;
      a0 += diff * double(g[0]);
      a1 += diff * double(g[1]);
      a2 += diff * double(g[2]);
      if constexpr (Laplacian) l += diff * double(cw[k]);
    }
    double* o = out + i * 9;
    for (int c = 0; c < 3; ++c) o[c * 3] = a0[c], o[c * 3 + 1] = a1[c], o[c * 3 + 2] = a2[c];
    if constexpr (Laplacian)
      for (int c = 0; c < 3; ++c) lap[i * 3 + c] = l[c];
  }
}

/// gradient<2, 2>, and the same optional Laplacian as gradient3.
template <class W, bool Laplacian = false>
void gradient2(std::size_t n, const Offset* off, const ParticleId* col, const W* w, const double* f,
               double* out, const W* cw = nullptr, double* lap = nullptr) {
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    v2 a0 = {}, a1 = {}, l = {};
    const v2 fi = {f[i * 2], f[i * 2 + 1]};
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const double* fj = f + static_cast<std::size_t>(col[k]) * 2;
      const v2 diff = v2{fj[0], fj[1]} - fi;
      const W* g = w + k * 2;
      a0 += diff * double(g[0]);
      a1 += diff * double(g[1]);
      if constexpr (Laplacian) l += diff * double(cw[k]);
    }
    double* o = out + i * 4;
    for (int c = 0; c < 2; ++c) o[c * 2] = a0[c], o[c * 2 + 1] = a1[c];
    if constexpr (Laplacian)
      for (int c = 0; c < 2; ++c) lap[i * 2 + c] = l[c];
  }
}

/// out[i*stride + c] = sum_b diag_i[b] q_i[c][b] + sum_{m : i in H_m} g_mi[b] q_m[c][b], over
/// the dual-support rows (off, col, w hold g_mi in dual order).
template <int D, int NC, class W>
void transpose(std::size_t n, const ParticleId* rows, const Offset* off, const ParticleId* col,
               const W* w, const double* diag, const double* q, double* out, std::size_t stride = NC) {
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row_of(rows, r);
    double acc[NC] = {};
    const double* qi = q + i * NC * D;
    for (int c = 0; c < NC; ++c)
      for (int b = 0; b < D; ++b) acc[c] += diag[i * D + b] * qi[c * D + b];
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const double* qm = q + static_cast<std::size_t>(col[k]) * NC * D;
      const W* g = w + k * D;
      for (int c = 0; c < NC; ++c)
        for (int b = 0; b < D; ++b) acc[c] += double(g[b]) * qm[c * D + b];
    }
    for (int c = 0; c < NC; ++c) out[i * stride + c] = acc[c];
  }
}

/// transpose<3, 3>: one accumulator per row c of q, lanes over b, summed at the end.
template <class W>
void transpose3(std::size_t n, const ParticleId* rows, const Offset* off, const ParticleId* col,
                const W* w, const double* diag, const double* q, double* out) {
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row_of(rows, r);
    const double* qi = q + i * 9;
    const v4 di = load3(diag + i * 3);
    v4 a0 = di * load3(qi), a1 = di * load3(qi + 3), a2 = di * load3(qi + 6);
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const double* qm = q + static_cast<std::size_t>(col[k]) * 9;
      const v4 g = load3(w + k * 3);
      a0 += g * load3(qm);
      a1 += g * load3(qm + 3);
      a2 += g * load3(qm + 6);
    }
    out[i * 3] = a0[0] + a0[1] + a0[2];
    out[i * 3 + 1] = a1[0] + a1[1] + a1[2];
    out[i * 3 + 2] = a2[0] + a2[1] + a2[2];
  }
}

/// transpose<2, 2>.
template <class W>
void transpose2(std::size_t n, const ParticleId* rows, const Offset* off, const ParticleId* col,
                const W* w, const double* diag, const double* q, double* out) {
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row_of(rows, r);
    const double* qi = q + i * 4;
    const v2 di = {diag[i * 2], diag[i * 2 + 1]};
    v2 a0 = di * v2{qi[0], qi[1]}, a1 = di * v2{qi[2], qi[3]};
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const double* qm = q + static_cast<std::size_t>(col[k]) * 4;
      const v2 g = {double(w[k * 2]), double(w[k * 2 + 1])};
      a0 += g * v2{qm[0], qm[1]};
      a1 += g * v2{qm[2], qm[3]};
    }
    out[i * 2] = a0[0] + a0[1];
    out[i * 2 + 1] = a1[0] + a1[1];
  }
}

/// out[i*stride + c] = sum_j sum_b (q_j - q_i)[c][b] g_ij[b] (the nonlocal divergence).
template <int D, int NC, class W>
void divergence(std::size_t n, const ParticleId* rows, const Offset* off, const ParticleId* col,
                const W* w, const double* q, double* out, std::size_t stride = NC) {
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row_of(rows, r);
    double acc[NC] = {};
    const double* qi = q + i * NC * D;
    for (Offset k = off[i]; k < off[i + 1]; ++k) {
      const double* qj = q + static_cast<std::size_t>(col[k]) * NC * D;
      const W* g = w + k * D;
      for (int c = 0; c < NC; ++c)
        for (int b = 0; b < D; ++b) acc[c] += (qj[c * D + b] - qi[c * D + b]) * double(g[b]);
    }
    for (int c = 0; c < NC; ++c) out[i * stride + c] = acc[c];
  }
}

/// gradient<D, NC> for any nc: one pass over the row per component.
template <int D, class W>
void gradient_any(std::size_t n, const Offset* off, const ParticleId* col, const W* w, const double* f,
                  int nc, std::size_t stride, double* out) {
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < nc; ++c) {
      double acc[D] = {};
      const double fi = f[i * stride + c];
      for (Offset k = off[i]; k < off[i + 1]; ++k) {
        const double diff = f[static_cast<std::size_t>(col[k]) * stride + c] - fi;
        for (int b = 0; b < D; ++b) acc[b] += diff * double(w[k * D + b]);
      }
      for (int b = 0; b < D; ++b) out[(i * nc + c) * D + b] = acc[b];
    }
}

/// transpose<D, NC> for any nc.
template <int D, class W>
void transpose_any(std::size_t n, const ParticleId* rows, const Offset* off, const ParticleId* col,
                   const W* w, const double* diag, const double* q, int nc, std::size_t stride, double* out) {
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row_of(rows, r);
    for (int c = 0; c < nc; ++c) {
      double acc = 0.0;
      const double* qi = q + (i * nc + c) * D;
      for (int b = 0; b < D; ++b) acc += diag[i * D + b] * qi[b];
      for (Offset k = off[i]; k < off[i + 1]; ++k) {
        const double* qm = q + (static_cast<std::size_t>(col[k]) * nc + c) * D;
        for (int b = 0; b < D; ++b) acc += double(w[k * D + b]) * qm[b];
      }
      out[i * stride + c] = acc;
    }
  }
}

/// divergence<D, NC> for any nc.
template <int D, class W>
void divergence_any(std::size_t n, const ParticleId* rows, const Offset* off, const ParticleId* col,
                    const W* w, const double* q, int nc, std::size_t stride, double* out) {
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row_of(rows, r);
    for (int c = 0; c < nc; ++c) {
      double acc = 0.0;
      const double* qi = q + (i * nc + c) * D;
      for (Offset k = off[i]; k < off[i + 1]; ++k) {
        const double* qj = q + (static_cast<std::size_t>(col[k]) * nc + c) * D;
        for (int b = 0; b < D; ++b) acc += (qj[b] - qi[b]) * double(w[k * D + b]);
      }
      out[i * stride + c] = acc;
    }
  }
}

}  // namespace perinom::kernels

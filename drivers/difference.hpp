#pragma once
// How far apart two answers to the same problem are (the Newton checks of `perinom run`).
#include <algorithm>
#include <cmath>
#include <vector>

namespace perinom::cli {

struct Difference {
  double relative_l2 = 0.0;   ///< |a - b| / |b|
  double relative_max = 0.0;  ///< max |a - b| / max |b|
};

/// a against the reference b (same length); plain norms where b is zero.
inline Difference difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d2 = 0, b2 = 0, dmax = 0, bmax = 0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    d2 += (a[k] - b[k]) * (a[k] - b[k]), b2 += b[k] * b[k];
    dmax = std::max(dmax, std::abs(a[k] - b[k])), bmax = std::max(bmax, std::abs(b[k]));
  }
  return {b2 > 0 ? std::sqrt(d2 / b2) : std::sqrt(d2), bmax > 0 ? dmax / bmax : dmax};
}

}  // namespace perinom::cli

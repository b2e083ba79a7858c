#include "condition_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace perinom::detail {
namespace {

double sum_abs(const std::vector<double>& v) {
  double s = 0.0;
  for (const double x : v) s += std::abs(x);
  return s;
}

}  // namespace

double inverse_norm1_estimate(std::size_t n, const FactorSolve& solve, const FactorSolve& solve_transposed) {
  if (n == 0) return 0.0;
  // Hager: the 1-norm of A^-1 x is largest, over |x|_1 = 1, at a unit vector e_j; the gradient
  // of |A^-1 x|_1 (A^-T sign(A^-1 x)) says which one to try next.
  std::vector<double> x(n, 1.0 / static_cast<double>(n)), y, z;
  double estimate = 0.0;
  for (int k = 0; k < 5; ++k) {
    y = x;
    solve(y);
    const double norm = sum_abs(y);
    if (!std::isfinite(norm)) return std::numeric_limits<double>::infinity();
    if (k > 0 && norm <= estimate) break;  // no longer growing
    estimate = norm;
    z.resize(n);
    for (std::size_t i = 0; i < n; ++i) z[i] = y[i] >= 0.0 ? 1.0 : -1.0;
    solve_transposed(z);
    std::size_t j = 0;
    double zx = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (std::abs(z[i]) > std::abs(z[j])) j = i;
      zx += z[i] * x[i];
    }
    if (!std::isfinite(z[j])) return std::numeric_limits<double>::infinity();
    if (k > 0 && std::abs(z[j]) <= zx) break;  // a local maximum
    std::fill(x.begin(), x.end(), 0.0);
    x[j] = 1.0;
  }
  // Higham's safeguard against the matrices that fool the search: an alternating, growing x.
  for (std::size_t i = 0; i < n; ++i)
    x[i] = (i % 2 ? -1.0 : 1.0) * (1.0 + (n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0));
  solve(x);
  const double safeguard = 2.0 * sum_abs(x) / (3.0 * static_cast<double>(n));
  if (!std::isfinite(safeguard)) return std::numeric_limits<double>::infinity();
  return std::max(estimate, safeguard);
}

double csr_norm1(std::int64_t n, const std::int64_t* row_ptr, const std::int64_t* col, const double* val) {
  std::vector<double> column(static_cast<std::size_t>(n), 0.0);
  for (std::int64_t k = 0; k < row_ptr[n]; ++k) column[static_cast<std::size_t>(col[k])] += std::abs(val[k]);
  double norm = 0.0;
  for (const double c : column) norm = std::max(norm, c);
  return norm;
}

}  // namespace perinom::detail

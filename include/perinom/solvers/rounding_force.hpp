#pragma once
/// @file The force that rounding alone leaves in an internal force evaluated at u.
#include <cmath>
#include <cstddef>
#include <limits>

#include "perinom/core/parallel.hpp"

namespace perinom {

/// The size of the terms an internal force at u sums: || (row_sum(k) |u_k|)_k ||_2 (N), with
/// row_sum(k) = sum_j |K_kj| over the n dofs.
template <class RowSum>
double stiffness_force(std::size_t n, const double* u, RowSum row_sum) {
  const double sum = parallel_sums<1>(n, [&row_sum, u](std::size_t k, double* s) {
    const double t = row_sum(k) * u[k];
    s[0] += t * t;
  })[0];
  return std::sqrt(sum);
}

/// The rounding in an internal force whose terms are `stiffness_force` in size: each carries a
/// relative error of eps, and u itself is stored to eps |u| (N). A residual force below it is
/// equilibrium to rounding, however small the loads and reactions it is measured against (a
/// stress-free rigid motion, whose reactions are rounding themselves). The factor 4: ADR's
/// residual on a translated 2-D bar (tests/cli/test_rounding_floor.cpp) still fell slowly
/// after 200,000 iterations, at 0.2 eps times the stiffness force; the floor sits 20 times
/// above that, where the displacements were right to 1e-11.
inline double rounding_force(double stiffness_force) {
  return 4.0 * std::numeric_limits<double>::epsilon() * stiffness_force;
}

}  // namespace perinom

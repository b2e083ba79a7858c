#pragma once
/// @file Small vector helpers shared by the solvers.
#include <cmath>
#include <vector>

#include "perinom/core/parallel.hpp"

namespace perinom {

inline double norm(const std::vector<double>& v) {
  const double* p = v.data();
  return std::sqrt(parallel_sums<1>(v.size(), [p](std::size_t k, double* s) { s[0] += p[k] * p[k]; })[0]);
}

}  // namespace perinom

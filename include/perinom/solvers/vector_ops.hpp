#pragma once
/// @file Small vector helpers shared by the solvers.
#include <cmath>
#include <vector>

namespace perinom {

inline double norm(const std::vector<double>& v) {
  double s = 0.0;
  for (const double x : v) s += x * x;
  return std::sqrt(s);
}

}  // namespace perinom

#include "perinom/materials/measures.hpp"

#include <cmath>

namespace perinom {

double mean_stress(const double* sigma3) { return (sigma3[0] + sigma3[4] + sigma3[8]) / 3.0; }

double equivalent_strain(const double* H, int d) {
  double eps[9] = {};
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) eps[a * 3 + b] = 0.5 * (H[a * d + b] + H[b * d + a]);
  const double tr = (eps[0] + eps[4] + eps[8]) / 3.0;
  double ee = 0.0;
  for (int k = 0; k < 9; ++k) {
    const double e = eps[k] - (k % 4 == 0 ? tr : 0.0);
    ee += e * e;
  }
  return std::sqrt(2.0 / 3.0 * ee);
}

}  // namespace perinom

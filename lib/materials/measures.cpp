#include "perinom/materials/measures.hpp"

#include <algorithm>
#include <cmath>

namespace perinom {

double mean_stress(const double* sigma3) { return (sigma3[0] + sigma3[4] + sigma3[8]) / 3.0; }

double max_principal_stress(const double* s) {
  // sigma = q I + p B with q = tr / 3, p^2 = |dev|^2 / 6 and det B = 2 cos(3 phi): the largest
  // eigenvalue is q + 2 p cos(phi).
  const double q = (s[0] + s[4] + s[8]) / 3.0;
  const double off = s[1] * s[1] + s[2] * s[2] + s[5] * s[5];
  const double d0 = s[0] - q, d1 = s[4] - q, d2 = s[8] - q;
  const double p2 = (d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * off) / 6.0;
  if (!(p2 > 0.0)) return q;
  const double p = std::sqrt(p2);
  const double b0 = d0 / p, b1 = d1 / p, b2 = d2 / p, b01 = s[1] / p, b02 = s[2] / p, b12 = s[5] / p;
  const double det = b0 * (b1 * b2 - b12 * b12) - b01 * (b01 * b2 - b12 * b02) + b02 * (b01 * b12 - b1 * b02);
  const double r = std::clamp(det / 2.0, -1.0, 1.0);
  return q + 2.0 * p * std::cos(std::acos(r) / 3.0);
}

double equivalent_strain(const double* H, int d, double eps_zz) {
  double eps[9] = {};
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) eps[a * 3 + b] = 0.5 * (H[a * d + b] + H[b * d + a]);
  if (d == 2) eps[8] = eps_zz;
  const double tr = (eps[0] + eps[4] + eps[8]) / 3.0;
  double ee = 0.0;
  for (int k = 0; k < 9; ++k) {
    const double e = eps[k] - (k % 4 == 0 ? tr : 0.0);
    ee += e * e;
  }
  return std::sqrt(2.0 / 3.0 * ee);
}

}  // namespace perinom

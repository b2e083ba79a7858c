#include "perinom/fracture/critical_stretch.hpp"

#include <cmath>
#include <stdexcept>

namespace perinom {

BondCalibration bond_calibration(const LinearElastic& m, Influence weight, double delta, double thickness) {
  BondCalibration c;
  c.dim = m.dim;
  c.bulk = m.lambda() + 2.0 * m.mu() / m.dim;
  c.weight = weight;
  c.delta = delta;
  c.thickness = thickness;
  return c;
}

double influence_moment(Influence weight, double delta, int n) {
  if (n < 2) throw std::invalid_argument("influence_moment: n must be at least 2");
  const double top = std::pow(delta, n + 1);
  switch (weight) {
    case Influence::constant: return top / (n + 1);
    case Influence::inverse_distance: return top / n;
    case Influence::inverse_square: return top / (n - 1);
    case Influence::gaussian: break;
  }
  // Simpson's rule on a smooth integrand: 2000 intervals leave 1e-13 relative.
  const int m = 2000;
  const double h = delta / m;
  double sum = 0.0;
  for (int k = 0; k <= m; ++k) {
    const double r = k * h;
    const double f = influence(weight, r, delta) * std::pow(r, n);
    sum += (k == 0 || k == m ? 1.0 : k % 2 ? 4.0 : 2.0) * f;
  }
  return sum * h / 3.0;
}

double micromodulus_scale(const BondCalibration& c) {
  if (c.dim == 3) return 9.0 * c.bulk / (2.0 * M_PI * influence_moment(c.weight, c.delta, 3));
  return 4.0 * c.bulk / (M_PI * c.thickness * influence_moment(c.weight, c.delta, 2));
}

double critical_stretch(const BondCalibration& c, double G_c) {
  if (!(G_c > 0.0)) throw std::invalid_argument("critical_stretch: G_c must be positive");
  if (!(c.bulk > 0.0) || !(c.delta > 0.0)) throw std::invalid_argument("critical_stretch: bulk modulus and horizon must be positive");
  auto I = [&](int n) { return influence_moment(c.weight, c.delta, n); };
  const double s2 = c.dim == 3 ? 4.0 * G_c * I(3) / (9.0 * c.bulk * I(4)) : M_PI * G_c * I(2) / (4.0 * c.bulk * I(3));
  return std::sqrt(s2);
}

double pair_energy(const BondCalibration& c, double r, double s) {
  return 0.5 * micromodulus_scale(c) * influence(c.weight, r, c.delta) * s * s * r;
}

}  // namespace perinom

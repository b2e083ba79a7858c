#include "perinom/materials/linear_elastic.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "perinom/core/error.hpp"

namespace perinom {

void check_material(const LinearElastic& m) {
  auto refuse = [](const char* field, double v, const char* rule) {
    char text[160];
    std::snprintf(text, sizeof text, "LinearElastic::%s = %g: %s", field, v, rule);
    throw InputError(text);
  };
  if (!(m.E > 0.0 && std::isfinite(m.E))) refuse("E", m.E, "must be positive and finite");
  if (!(m.nu > -1.0 && m.nu < 0.5)) refuse("nu", m.nu, "must lie in (-1, 0.5)");
  if (!(m.density > 0.0 && std::isfinite(m.density))) refuse("density", m.density, "must be positive and finite");
  if (m.dim != 2 && m.dim != 3) refuse("dim", m.dim, "must be 2 or 3");
}

double LinearElastic::lambda() const {
  const double lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  if (plane == PlaneCondition::stress) return 2.0 * lam * mu() / (lam + 2.0 * mu());
  return lam;
}

void LinearElastic::stress(const double* H, double* P) const {
  const int d = dim;
  const double lam = lambda(), m = mu();
  double tr = 0.0;
  for (int a = 0; a < d; ++a) tr += H[a * d + a];
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b)
      P[a * d + b] = m * (H[a * d + b] + H[b * d + a]) + (a == b ? lam * tr : 0.0);
}

double LinearElastic::energy(const double* H) const {
  const int d = dim;
  double P[9];
  stress(H, P);
  double w = 0.0;
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) w += 0.5 * P[a * d + b] * 0.5 * (H[a * d + b] + H[b * d + a]);
  return w;
}

void LinearElastic::tangent(double* C) const {
  const int d = dim;
  const double lam = lambda(), m = mu();
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b)
      for (int c = 0; c < d; ++c)
        for (int e = 0; e < d; ++e)
          C[((a * d + b) * d + c) * d + e] = lam * (a == b) * (c == e) +
                                             m * ((a == c) * (b == e) + (a == e) * (b == c));
}

void LinearElastic::stress3(const double* H, double* s) const {
  const int d = dim;
  double P[9];
  stress(H, P);
  for (int k = 0; k < 9; ++k) s[k] = 0.0;
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) s[a * 3 + b] = P[a * d + b];
  if (d == 2 && plane == PlaneCondition::strain) s[8] = lambda() * (H[0] + H[3]);
}

double von_mises(const double* s) {
  const double dxy = s[0] - s[4], dyz = s[4] - s[8], dzx = s[8] - s[0];
  const double shear = s[1] * s[1] + s[5] * s[5] + s[2] * s[2];
  return std::sqrt(0.5 * (dxy * dxy + dyz * dyz + dzx * dzx) + 3.0 * shear);
}

}  // namespace perinom

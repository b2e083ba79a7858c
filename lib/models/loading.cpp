#include "perinom/models/loading.hpp"

#include <algorithm>
#include <cmath>

namespace perinom {

void Loading::fix(std::int64_t dof, double v) {
  for (std::size_t k = 0; k < fixed.size(); ++k)
    if (fixed[k] == dof) {
      value[k] = v;
      return;
    }
  fixed.push_back(dof);
  value.push_back(v);
}

void Loading::impose(double s, double* u) const {
  if (couplings.empty()) {
    for (std::size_t k = 0; k < fixed.size(); ++k) u[fixed[k]] = target(s, k);
    return;
  }
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    double sum = 0.0;
    for (Offset c = couplings[k]; c < couplings[k + 1]; ++c) sum += coef[c] * u[coupled[c]];
    u[fixed[k]] = scale[k] * (target(s, k) - sum);
  }
}

double Loading::force_norm(double s) const {
  if (!has_force()) return 0.0;
  const std::size_t n = std::max(force.size(), force0.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) sum += force_at(s, k) * force_at(s, k);
  return std::sqrt(sum);
}

void Loading::begin_stage(const Loading* previous, const double* u) {
  value0.assign(fixed.size(), 0.0);
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    double v = u[fixed[k]];
    if (coupled_constraints()) {
      v /= scale[k];
      for (Offset c = couplings[k]; c < couplings[k + 1]; ++c) v += coef[c] * u[coupled[c]];
    }
    value0[k] = v;
  }
  force0.clear();
  if (previous && previous->has_force()) {
    const std::size_t n = std::max(previous->force.size(), previous->force0.size());
    force0.resize(n);
    for (std::size_t k = 0; k < n; ++k) force0[k] = previous->force_at(1.0, k);
  }
  pressure_force0.clear();
  if (previous && previous->has_pressure()) {
    const std::size_t n = std::max(previous->pressure_force.size(), previous->pressure_force0.size());
    pressure_force0.resize(n);
    for (std::size_t k = 0; k < n; ++k) pressure_force0[k] = previous->pressure_force_at(1.0, k);
  }
}

void Loading::zero_fixed(double* r) const {
  for (const auto dof : fixed) r[dof] = 0.0;
}

}  // namespace perinom

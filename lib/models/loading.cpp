#include "perinom/models/loading.hpp"

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
    for (std::size_t k = 0; k < fixed.size(); ++k) u[fixed[k]] = s * value[k];
    return;
  }
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    double sum = 0.0;
    for (Offset c = couplings[k]; c < couplings[k + 1]; ++c) sum += coef[c] * u[coupled[c]];
    u[fixed[k]] = scale[k] * (s * value[k] - sum);
  }
}

void Loading::zero_fixed(double* r) const {
  for (const auto dof : fixed) r[dof] = 0.0;
}

}  // namespace perinom

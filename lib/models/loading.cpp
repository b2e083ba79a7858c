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
  for (std::size_t k = 0; k < fixed.size(); ++k) u[fixed[k]] = s * value[k];
}

void Loading::zero_fixed(double* r) const {
  for (const auto dof : fixed) r[dof] = 0.0;
}

}  // namespace perinom

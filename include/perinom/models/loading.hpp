#pragma once
/// @file Boundary conditions reduced to what a solver applies: fixed degrees of freedom
/// with prescribed values, and an external force vector, both at full load.
#include <cstdint>
#include <vector>

namespace perinom {

/// A load at factor s in [0, 1] prescribes u[fixed[k]] = s * value[k] and applies s * force.
struct Loading {
  std::vector<std::int64_t> fixed;  ///< degree-of-freedom indices (i*dofs_per_particle + a)
  std::vector<double> value;        ///< prescribed displacement at full load (m)
  std::vector<double> force;        ///< external force at full load (N), one per dof

  /// Adds a constraint, replacing an earlier one on the same dof.
  void fix(std::int64_t dof, double v);
  /// Sets u at the constrained dofs to s * value.
  void impose(double s, double* u) const;
  /// Zeros the constrained entries of r (a residual or a velocity).
  void zero_fixed(double* r) const;
};

}  // namespace perinom

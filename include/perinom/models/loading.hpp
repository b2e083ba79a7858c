#pragma once
/// @file Boundary conditions reduced to what a solver applies: fixed degrees of freedom
/// with prescribed values, and an external force vector, both at full load.
#include <cstdint>
#include <vector>

#include "perinom/core/types.hpp"

namespace perinom {

/// A load at factor s in [0, 1] applies s * force and prescribes, for each constrained
/// degree of freedom k, either u[fixed[k]] = s * value[k] (the particle itself: the seed's
/// "outer layer" condition), or, when the constraint has couplings, the value at a point
/// off the particle through its first-order reconstruction u_i + (grad u)_i . d = s * value
/// (a face-located condition). The latter reads
///   u[fixed[k]] = scale[k] * (s * value[k] - sum_c coef[c] u[coupled[c]]),
/// c over couplings[k] .. couplings[k+1).
struct Loading {
  std::vector<std::int64_t> fixed;  ///< degree-of-freedom indices (i*dofs_per_particle + a)
  std::vector<double> value;        ///< prescribed displacement at full load (m)
  std::vector<double> force;        ///< external force at full load (N), one per dof
  // Couplings of face-located constraints (empty when every constraint is on its particle).
  std::vector<Offset> couplings;    ///< CSR offsets, fixed.size() + 1 entries
  std::vector<std::int64_t> coupled;
  std::vector<double> coef, scale;

  /// Adds a constraint, replacing an earlier one on the same dof.
  void fix(std::int64_t dof, double v);
  /// Sets u at the constrained dofs. Face-located constraints use the current neighbour
  /// values (one Gauss-Seidel sweep; the explicit solvers call it every iteration, so the
  /// constraints converge with the solve).
  void impose(double s, double* u) const;
  /// Zeros the constrained entries of r (a residual or a velocity).
  void zero_fixed(double* r) const;
  bool coupled_constraints() const { return !coupled.empty(); }
};

}  // namespace perinom

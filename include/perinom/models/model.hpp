#pragma once
/// @file What a solver needs from the physics: residual pieces, energy, a stiffness bound.
#include <cstddef>
#include <string>
#include <vector>

namespace perinom {

struct Loading;

/// A discrete model with dofs_per_particle() unknowns per particle, stored point-major.
/// Solvers own the time loop; models only evaluate. Workspaces are allocated once, so
/// internal_force() never allocates.
class Model {
 public:
  virtual ~Model() = default;
  virtual std::size_t particles() const = 0;
  virtual int dofs_per_particle() const = 0;
  std::size_t dofs() const { return particles() * dofs_per_particle(); }

  /// f = dW/du, the internal force (N) at displacement u (m).
  virtual void internal_force(const double* u, double* f) = 0;
  /// W(u), the stored energy (J), stabilization included.
  virtual double energy(const double* u) = 0;
  /// Lumped mass per degree of freedom (kg).
  virtual std::vector<double> lumped_mass() const = 0;
  /// sum_j |K_ij| per degree of freedom (N/m), K the stiffness at the reference state.
  virtual std::vector<double> stiffness_row_sums() const = 0;
  /// Bytes held by the assembled operators, by name (for `perinom check`).
  virtual std::vector<std::pair<std::string, std::size_t>> memory() const = 0;
  /// Solvers call this before evaluating forces under `loading` at factor s, for loads the
  /// model itself carries (follower pressures); most models carry none.
  virtual void follow_loads(const Loading& loading, double s) { (void)loading, (void)s; }
};

}  // namespace perinom

#pragma once
/// @file The stability check: the eigenvalues of M^-1 K on the free degrees of freedom (all of
/// them densely, or the inertia of a symmetric K sparsely), and whether the problem is stable.
///
/// K is the model's stiffness dF/du at the reference state (visit_tangent_rows), reduced to
/// the free dofs in Galerkin form: u = T u_R, K_T = T^T K T, M_T = T^T M T with M the lumped
/// mass. A plain fixed dof has a zero row in T (K_T = K_RR, M_T = M_RR); a face-located
/// constraint u_F = scale (t - sum coef u_c) (loading.hpp) gives, with t = 0, u_F = A_FF u_F
/// + A_FR u_R, so T's constrained rows are (I - A_FF)^-1 A_FR (couplings among constrained
/// dofs included). The eigenvalues are those of L^-1 K_T L^-T with M_T = L L^T, which is
/// symmetric whenever K_T is, so a symmetric model's spectrum is real to rounding.
///
/// A symmetric K with a positive mass has real eigenvalues, and none negative when K is
/// positive semi-definite: the explicit solver then oscillates at sqrt(lambda). A negative
/// lambda, or a complex one, makes e^(sqrt(-lambda) t) a solution of M u'' + K u = 0: it
/// grows at the rate Im sqrt(lambda) (1/s) whatever the time step.
#include <cstddef>
#include <string>

#include "perinom/models/loading.hpp"
#include "perinom/models/tangent_model.hpp"

namespace perinom {

struct SpectrumOptions {
  /// A reduced stiffness symmetric to symmetric_tolerance (relative, Frobenius) is checked by
  /// its inertia (sparse, any size; lib/solvers/inertia.hpp) instead of the dense solve.
  bool sparse_when_symmetric = true;
  double symmetric_tolerance = 1e-12;
  /// The largest number of free dofs the dense solve (non-symmetric stiffness) accepts: memory 8 n^2 bytes per dense
  /// copy, time O(n^3) on one core (Eigen's EigenSolver): measured 0.5 s at 490 free dofs and
  /// 140 s at 1,980 (the vibrating bar at dx 1 mm) on a shared 2-core machine, so minutes at
  /// this limit (docs/scene-format.md).
  std::size_t max_dofs = 2000;
  /// An eigenvalue counts as complex when |Im lambda| > complex_tolerance * max |lambda|.
  double complex_tolerance = 1e-8;
  /// ... and as negative when Re lambda < -negative_tolerance * max |lambda|.
  double negative_tolerance = 1e-9;
};

/// The eigenvalues of M^-1 K (1/s^2) summarized.
struct SpectrumReport {
  std::size_t dofs = 0;            ///< free dofs: the size of the dense problem
  double min_real = 0.0;           ///< the smallest real part (1/s^2)
  double max_abs = 0.0;            ///< the largest |lambda| (1/s^2)
  double max_imag_relative = 0.0;  ///< max |Im lambda| / max |lambda|
  std::size_t negative = 0;        ///< eigenvalues with Re < -negative_tolerance * max |lambda|
  std::size_t complex = 0;         ///< eigenvalues with |Im| > complex_tolerance * max |lambda|
  double symmetry_defect = 0.0;    ///< ||K_T - K_T^T||_F / ||K_T||_F
  double growth_rate = 0.0;        ///< max Im sqrt(lambda) (1/s), principal root
  double seconds = 0.0;            ///< wall time of the check
  std::string method;              ///< "dense" (all eigenvalues), "sparse Cholesky: positive definite"
                                   ///< or "sparse LDL^T inertia" (K not positive definite)
  std::size_t singular = 0;        ///< sparse: zero pivots (an unconstrained rigid mode)

  /// No negative and no complex eigenvalue beyond the tolerances.
  bool stable() const { return negative == 0 && complex == 0; }
  /// "stable", or "UNSTABLE: N negative and M complex eigenvalues, growth rate G 1/s".
  std::string verdict() const;
};

/// The number of free dofs of a loading on a model (the size the check would solve).
std::size_t free_dofs(const TangentModel& model, const Loading& loading);

/// Assembles K_T and M_T. A symmetric K_T (consistent, classical): the count of negative
/// eigenvalues from the inertia of K_T, the extreme ones by iteration; a symmetric matrix has
/// no complex eigenvalue. Otherwise all eigenvalues of M_T^-1 K_T densely (Eigen's
/// EigenSolver, no eigenvectors). The tangent is evaluated at u = 0 (prepare_tangent).
/// Throws InputError when a non-symmetric K_T's free dofs exceed options.max_dofs.
SpectrumReport stiffness_spectrum(TangentModel& model, const Loading& loading,
                                  const SpectrumOptions& options = {});

}  // namespace perinom

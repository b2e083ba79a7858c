#pragma once
/// @file Newton's method on the assembled Jacobian: SUNDIALS KINSOL with a sparse direct
/// solver, UMFPACK or KLU (THEORY sec. 8), the design's independent check of the explicit solvers.
#include <functional>
#include <string>
#include <vector>

#include "perinom/core/progress.hpp"
#include "perinom/models/tangent_model.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/solvers/adr.hpp"

namespace perinom {

struct NewtonOptions {
  double tolerance = 1e-10;       ///< max-norm of R over max-norm of R at the step's start
  double step_tolerance = 1e-14;  ///< KINSOL's scaled step tolerance
  int max_iterations = 50;        ///< per load step
  int load_steps = 1;
  bool line_search = true;
  /// The linear solver of each Newton step: "umfpack" or "klu" (KINSOL on the Jacobian with
  /// multipliers, factored by UMFPACK's multifrontal LU, BLAS-3 on dense fronts, or by KLU's
  /// left-looking sparse LU: the same steps to rounding; umfpack_linear_solver.hpp), or
  /// through PETSc SNES on the Galerkin-reduced system K_T = T^T K T
  /// (direct.hpp): "mumps" (MUMPS's multifrontal LU) or "gamg" (PETSc's algebraic multigrid
  /// preconditioning conjugate gradients, GMRES for a model with history). The PETSc ones
  /// need the Galerkin form of any face-located constraint (not the improved or strong
  /// formulation) and a build with PETSc. On a model spread over MPI ranks
  /// (DistributedModel) they solve over the ranks (face-located constraints there in the
  /// multiplier form, "mumps" only); "umfpack" and "klu" factor on one process (mpirun's
  /// driver takes "mumps" for them).
  std::string linear_solver = "umfpack";
  /// gamg: the particles' positions (point-major, dimension values each) of a solid, whose
  /// rigid-body modes then form the near-null space; empty: PETSc's default (constants).
  std::vector<double> positions;
  int dimension = 0;
  /// "umfpack", "klu": the bytes the whole process may hold once the Jacobian is factored (the
  /// command line's --max-memory); 0: the factors alone must fit in the memory available.
  /// Checked before the first factorization against the ordering's fill (factor_memory.hpp): a solve
  /// that would not fit throws InputError naming solver.linear_solver.
  double memory_limit = 0.0;
  /// The least load (N) the reported relative residual is taken over: its denominator is the
  /// larger of the step's loads and reactions and this. A load path passes the largest load or
  /// reaction its earlier stages carried: a stage that unloads the body to rest has loads and
  /// reactions that are rounding (1e-10 N after 2e4 N), over which a converged step read 1.36.
  /// KINSOL's convergence test does not use it.
  double load_floor = 0.0;
  /// Runs as each load step begins (the plastic path's ModelHistory::begin_step).
  std::function<void(int step)> before_step;
  /// Runs after each converged load step with its number, the Newton iterations it took and
  /// its relative residual (the plastic path commits here).
  std::function<void(int step, const std::vector<double>& u, long iterations, double residual)> after_step;
};

/// Solves the static problem of any model with tangent rows (correspondence, thin plate) in load steps s = 1/n ... 1. The Jacobian's pattern is built
/// once and the factorization's symbolic analysis is kept across iterations and load steps; only the
/// numeric factorization is redone. report.residual is the relative residual as ADR
/// defines it (|R_free| over the load norm), report.iterations the Newton iterations over
/// all steps. Throws InputError when the stiffness is singular (a body free to move
/// rigidly: a missing boundary condition); a solve that fails otherwise returns with
/// report.failure set.
SolveReport solve_newton(TangentModel& model, const Loading& loading,
                         const NewtonOptions& options, std::vector<double>& u,
                         Progress* progress = nullptr);

namespace detail {
/// Appends the supports' reactions at u (load factor s) to the history's last row (both
/// Newton paths); fint and reactions are the caller's scratch.
void append_reactions(TangentModel& model, const Loading& loading, double s, const double* u, std::vector<double>& fint,
                      std::vector<double>& reactions, History& history);

/// solve_newton with a PETSc linear solver (newton_petsc.cpp; the same report, with the
/// linear iterations per load step in the history).
SolveReport solve_newton_petsc(TangentModel& model, const Loading& loading, const NewtonOptions& options,
                               std::vector<double>& u, Progress* progress);
}  // namespace detail

}  // namespace perinom

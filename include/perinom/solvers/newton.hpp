#pragma once
/// @file Newton's method on the assembled Jacobian: SUNDIALS KINSOL with the KLU sparse
/// direct solver (THEORY sec. 8), the design's independent check of the explicit solvers.
#include <functional>
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
  /// Runs after each converged load step with its number, the Newton iterations it took and
  /// its relative residual (the plastic path commits here).
  std::function<void(int step, const std::vector<double>& u, long iterations, double residual)> after_step;
};

/// Solves the static problem of any model with tangent rows (correspondence, thin plate) in load steps s = 1/n ... 1. The Jacobian's pattern is built
/// once and KLU's symbolic analysis is kept across iterations and load steps; only the
/// numeric factorization is redone. report.residual is the relative residual as ADR
/// defines it (|R_free| over the load norm), report.iterations the Newton iterations over
/// all steps. Throws InputError when the stiffness is singular (a body free to move
/// rigidly: a missing boundary condition); a solve that fails otherwise returns with
/// report.failure set.
SolveReport solve_newton(TangentModel& model, const Loading& loading,
                         const NewtonOptions& options, std::vector<double>& u,
                         Progress* progress = nullptr);

}  // namespace perinom

#pragma once
/// @file A SUNDIALS linear solver on UMFPACK for KINSOL's CSR Jacobian: multifrontal LU,
/// whose dense frontal matrices run through BLAS-3. Nonlocal Jacobians couple each particle
/// to every particle within two horizons, so their factors fill in densely (3-D above all),
/// where KLU's left-looking sparse kernel, made for circuit matrices, is slow: on a 3-D
/// Drucker-Prager footing of 1,600 particles (4,800 dofs) a Newton iteration took 11.7 s with
/// KLU (docs/performance.md).
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

namespace perinom::detail {

/// What the last factorization found.
struct FactorState {
  bool singular = false;       ///< UMFPACK: a zero pivot (the matrix is singular)
  bool out_of_memory = false;  ///< the symbolic or numeric step ran out of memory
  double rcond = 0.0;          ///< min |U_ii| / max |U_ii| (KLU's klu_rcond measure); 0 before any
  double lu_entries = 0.0;     ///< UMFPACK: entries of L and U, L's unit diagonal not counted; 0 before any
};

/// A direct (matrix-based) SUNLinearSolver: setup factors the CSR matrix (the symbolic
/// analysis is kept while its pattern stays), solve runs UMFPACK's solve with its iterative
/// refinement. Free it with SUNLinSolFree.
SUNLinearSolver umfpack_linear_solver(SUNContext context);

/// The state of the last factorization of a solver made by umfpack_linear_solver.
FactorState umfpack_factor_state(SUNLinearSolver solver);

/// The 1-norm condition number of the last matrix A factored, estimated from solves with its
/// factors (condition_estimate.hpp); infinite when it had a zero pivot.
double umfpack_condition_number(SUNLinearSolver solver, SUNMatrix A);

}  // namespace perinom::detail

#pragma once
/// @file A linear static problem solved by one sparse Cholesky factorization: the stiffness K
/// (TangentModel::visit_tangent_rows) reduced to the free dofs in Galerkin form, K_T = T^T K T
/// with u = T u_R + u_p (spectrum.hpp describes T), factored by CHOLMOD's supernodal Cholesky.
/// For symmetric positive definite K_T only (the consistent and classical formulations, the
/// thin plate, once the constraints remove the rigid modes); a model with history
/// (plasticity) is not linear and needs newton, adr or lbc.
#include "perinom/core/progress.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/models/tangent_model.hpp"
#include "perinom/solvers/adr.hpp"

namespace perinom {

struct DirectOptions {
  /// The solve is checked by the residual of the model's own force: |T^T (f - F(u))| /
  /// |T^T f| (f the external force, F the internal one) must be below this, else the report
  /// says it did not converge.
  double tolerance = 1e-8;
  /// The bytes the whole process may hold once K_T is factored (the command line's
  /// --max-memory); 0: the factor alone must fit in the memory available. Checked after
  /// CHOLMOD's analysis, before the factorization (factor_memory.hpp): a factor that would
  /// not fit throws InputError naming solver.type.
  double memory_limit = 0.0;
};

/// u (resized to model.dofs()) at full load. The report: converged, residual (the check
/// above), iterations = 1 plus the steps of iterative refinement on the same factor (up to
/// 3, taken only while the residual is above the tolerance: rounding in a badly conditioned
/// K_T, e.g. nu near 1/2), and `failure` naming what went wrong (K_T not positive definite:
/// a non-symmetric formulation or a rigid mode left free; a residual still above the
/// tolerance). A solution whose sum of squares is not finite fails the NaN/Inf guard of ADR
/// and Newton: `diverged`, diverged_at 1, iterations 0 and u the unloaded state (zeros).
/// Throws InputError for a model
/// with history or collocated constraints.
SolveReport solve_direct(TangentModel& model, const Loading& loading, std::vector<double>& u,
                         const DirectOptions& options = {}, Progress* progress = nullptr);

}  // namespace perinom

#include "perinom/solvers/newton.hpp"

#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <type_traits>

#include "perinom/core/error.hpp"
#include "perinom/core/memory.hpp"
#include "perinom/solvers/jacobian.hpp"
#include "perinom/solvers/rounding_force.hpp"
#include "perinom/solvers/vector_ops.hpp"
#include "condition_estimate.hpp"
#include "factor_memory.hpp"
#include "singular_stiffness.hpp"
#include "umfpack_linear_solver.hpp"

namespace perinom {
namespace {

// RAII for the SUNDIALS objects: each is freed by its own function.
struct ContextDeleter { void operator()(SUNContext c) const { SUNContext_Free(&c); } };
struct VectorDeleter { void operator()(N_Vector v) const { N_VDestroy(v); } };
struct MatrixDeleter { void operator()(SUNMatrix m) const { SUNMatDestroy(m); } };
struct SolverDeleter { void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); } };
struct KinsolDeleter { void operator()(void* k) const { KINFree(&k); } };
using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, SolverDeleter>;
using Kinsol = std::unique_ptr<void, KinsolDeleter>;

void check(int flag, const char* what) {
  if (flag < 0) throw SolveError(std::string("Newton: ") + what + " failed (SUNDIALS flag " + std::to_string(flag) + ")");
}

struct Data {
  StaticSystem* system;
  double s;
  Progress* progress = nullptr;
  ProgressSample* sample = nullptr;  // the load step's; its iteration counts Jacobians
};

int residual(N_Vector u, N_Vector R, void* user) {
  auto* data = static_cast<Data*>(user);
  data->system->residual(N_VGetArrayPointer(u), data->s, N_VGetArrayPointer(R));
  const double* r = N_VGetArrayPointer(R);
  for (sunindextype k = 0; k < N_VGetLength(R); ++k)
    if (!std::isfinite(r[k])) return 1;  // recoverable: the line search steps back
  return 0;
}

int jacobian(N_Vector u, N_Vector, SUNMatrix J, void* user, N_Vector, N_Vector) {
  auto* data = static_cast<Data*>(user);
  if (data->progress) {  // a Jacobian per iteration: the one sign of life inside a long load step
    ++data->sample->iteration;
    data->progress->update(*data->sample);
  }
  data->system->assemble(N_VGetArrayPointer(u));
  const CsrMatrix& A = data->system->jacobian();
  std::memcpy(SM_INDEXPTRS_S(J), A.row_ptr.data(), A.row_ptr.size() * sizeof(sunindextype));
  std::memcpy(SM_INDEXVALS_S(J), A.col.data(), A.col.size() * sizeof(sunindextype));
  std::memcpy(SM_DATA_S(J), A.val.data(), A.val.size() * sizeof(double));
  return 0;
}

/// KLU's reciprocal pivot ratio after the last factorization (0 if none succeeded).
double reciprocal_pivot_ratio(SUNLinearSolver ls) {
  sun_klu_common* common = SUNLinSol_KLUGetCommon(ls);
  sun_klu_symbolic* symbolic = SUNLinSol_KLUGetSymbolic(ls);
  sun_klu_numeric* numeric = SUNLinSol_KLUGetNumeric(ls);
  if (!common || !symbolic || !numeric) return 0.0;
  if (!sun_klu_rcond(symbolic, numeric, common)) return 0.0;
  return common->rcond;
}

/// The 1-norm condition number of the matrix KLU factored last (J), estimated from solves with
/// its factors; infinite when it has none.
double klu_condition_number(SUNLinearSolver ls, SUNMatrix J) {
  static_assert(std::is_same_v<sun_klu_common, klu_l_common>, "KLU's long interface, as SUNDIALS' 64-bit indices");
  sun_klu_common* common = SUNLinSol_KLUGetCommon(ls);
  sun_klu_symbolic* symbolic = SUNLinSol_KLUGetSymbolic(ls);
  sun_klu_numeric* numeric = SUNLinSol_KLUGetNumeric(ls);
  if (!common || !symbolic || !numeric || common->status != KLU_OK) return std::numeric_limits<double>::infinity();
  const sunindextype n = SM_ROWS_S(J);
  const auto with = [&](bool transposed) {
    return [&, transposed](std::vector<double>& x) {
      if (transposed) klu_l_solve(symbolic, numeric, n, 1, x.data(), common);
      else klu_l_tsolve(symbolic, numeric, n, 1, x.data(), common);
    };
  };
  // SUNDIALS factors the CSR matrix read as CSC, A^T: KLU's transposed solve solves A x = b.
  return detail::csr_norm1(n, SM_INDEXPTRS_S(J), SM_INDEXVALS_S(J), SM_DATA_S(J)) *
         detail::inverse_norm1_estimate(static_cast<std::size_t>(n), with(false), with(true));
}

/// The factorization's findings, from whichever of the two direct solvers ran.
detail::FactorState factor_state(SUNLinearSolver ls, bool umfpack) {
  if (umfpack) return detail::umfpack_factor_state(ls);
  detail::FactorState state;
  const sun_klu_common* common = SUNLinSol_KLUGetCommon(ls);
  state.singular = common && common->status == KLU_SINGULAR;
  state.out_of_memory = common && common->status == KLU_OUT_OF_MEMORY;
  state.rcond = reciprocal_pivot_ratio(ls);
  return state;
}

}  // namespace

namespace detail {
void append_reactions(TangentModel& model, const Loading& loading, double s, const double* u, std::vector<double>& fint,
                      std::vector<double>& reactions, History& history) {
  model.follow_loads(loading, s);
  model.internal_force(u, fint.data());
  loading.reactions(fint.data(), s, model.dofs_per_particle(), reactions.data());
  model.sum_across_ranks(reactions.data(), static_cast<int>(reactions.size()));  // a rank's share
  history.values.insert(history.values.end(), reactions.begin(), reactions.end());
}
}  // namespace detail

SolveReport solve_newton(TangentModel& model, const Loading& loading,
                         const NewtonOptions& opt, std::vector<double>& u, Progress* progress) {
  check_loading(loading, model.dofs());
  if (opt.load_steps < 1)
    throw InputError("NewtonOptions::load_steps = " + std::to_string(opt.load_steps) + ": must be at least 1");
  static_assert(sizeof(sunindextype) == sizeof(std::int64_t), "SUNDIALS must use 64-bit indices");
  const bool umfpack = opt.linear_solver == "umfpack";
  if (!umfpack && opt.linear_solver != "klu") return detail::solve_newton_petsc(model, loading, opt, u, progress);
  const char* factorizer = umfpack ? "UMFPACK" : "KLU";
  u.resize(model.dofs(), 0.0);
  StaticSystem system(model, loading);
  // The unknowns: u, then the multipliers of face-located constraints (kept across steps as
  // the next step's first guess).
  const std::size_t n = system.dofs();
  std::vector<double> z(u);
  z.resize(n, 0.0);
  const auto to_u = [&] { std::copy_n(z.begin(), u.size(), u.begin()); };
  SolveReport rep;
  rep.history.columns = {"load_step", "load_factor", "newton_iterations", "residual"};
  const int dpp = model.dofs_per_particle();
  for (const auto& c : loading.reaction_columns(dpp)) rep.history.columns.push_back(c);
  std::vector<double> fint(loading.has_supports() ? n : 0), reactions(loading.support_names.size() * dpp);

  SUNContext raw_ctx = nullptr;
  check(SUNContext_Create(nullptr, &raw_ctx), "SUNContext_Create");
  Context ctx(raw_ctx);
  Vector y(N_VMake_Serial(n, z.data(), ctx.get()));
  Vector ones(N_VNew_Serial(n, ctx.get())), fscale(N_VNew_Serial(n, ctx.get()));
  N_VConst(1.0, ones.get());
  const CsrMatrix& A = system.jacobian();
  Matrix J(SUNSparseMatrix(n, n, static_cast<sunindextype>(A.col.size()), CSR_MAT, ctx.get()));
  LinearSolver ls(umfpack ? detail::umfpack_linear_solver(ctx.get()) : SUNLinSol_KLU(y.get(), J.get(), ctx.get()));
  if (!J || !ls) throw SolveError("Newton: out of memory for the Jacobian (" + std::to_string(A.col.size()) + " nonzeros)");
  // KLU: AMD (on A + A^T) rather than SUNDIALS' default COLAMD: the Jacobian's pattern is
  // symmetric, and AMD fills less (plate with a hole, 4,968 dofs: L + U 4.6 M entries
  // against 5.5 M) and factorizes 15-18% faster (plate with a hole, biaxial test 3).
  // (UMFPACK orders by CAMD on A + A^T with the multipliers last: fill_ordering.hpp. KLU's
  // BTF permutes the multipliers' rows onto nonzero diagonals first, so KLU keeps AMD; its
  // peak on the plate with a hole was 9.5% above the prediction from that ordering's count.)
  if (!umfpack) check(SUNLinSol_KLUSetOrdering(ls.get(), 0), "SUNLinSol_KLUSetOrdering");
  const auto condition_number = [&] {
    return umfpack ? detail::umfpack_condition_number(ls.get(), J.get()) : klu_condition_number(ls.get(), J.get());
  };
  const detail::FactorPrediction factors = detail::predict_lu_factors(A);
  if (progress) {
    char what[200];
    std::snprintf(what, sizeof what,
                  "Newton: %s's LU factors, predicted from the ordering's fill: %.3g entries, about %.0f MiB beside the %.0f MiB "
                  "the process holds",
                  factorizer, factors.entries, factors.bytes / 1048576.0, resident_bytes() / 1048576.0);
    progress->phase(what);
  }
  char subject[300];
  std::snprintf(subject, sizeof subject,
                "solver.linear_solver: %s's LU factors of the Jacobian (%lld unknowns, %.3g entries; %.3g in L + U by "
                "the ordering's fill)",
                factorizer, static_cast<long long>(A.rows), double(A.col.size()), factors.entries);
  detail::require_factor_memory(factors.bytes, subject,
                                "use solver.linear_solver gamg (PETSc's multigrid: no factors) or mumps (a smaller "
                                "fill, or more processes under mpirun), solver.type adr, or a larger discretization.dx",
                                opt.memory_limit);
  Kinsol kin(KINCreate(ctx.get()));
  ProgressSample sample;
  sample.limit = 0;  // Newton's iteration count is no measure of the time left
  sample.load_steps = opt.load_steps;
  Data data{&system, 0.0, progress, &sample};
  check(KINInit(kin.get(), residual, y.get()), "KINInit");
  check(KINSetUserData(kin.get(), &data), "KINSetUserData");
  check(KINSetLinearSolver(kin.get(), ls.get(), J.get()), "KINSetLinearSolver");
  check(KINSetJacFn(kin.get(), jacobian), "KINSetJacFn");
  check(KINSetMaxSetupCalls(kin.get(), 1), "KINSetMaxSetupCalls");  // a fresh Jacobian every iteration
  check(KINSetNumMaxIters(kin.get(), opt.max_iterations), "KINSetNumMaxIters");
  check(KINSetFuncNormTol(kin.get(), opt.tolerance), "KINSetFuncNormTol");
  check(KINSetScaledStepTol(kin.get(), opt.step_tolerance), "KINSetScaledStepTol");
  // No cap on a Newton step's length: KINSOL's default, 1000 (metres here) from a zero start,
  // stopped a linear scene in which a unit mistake made the displacements that large (flag
  // KIN_MXNEWT_5X_EXCEEDED) where one step solves it; the run then says the answer is not small.
  check(KINSetMaxNewtonStep(kin.get(), 1e100), "KINSetMaxNewtonStep");
  check(KINSetPrintLevel(kin.get(), 0), "KINSetPrintLevel");
  check(KINSetErrHandlerFn(kin.get(), [](int, const char*, const char*, char*, void*) {}, nullptr), "KINSetErrHandlerFn");

  std::vector<double> R(n);
  std::vector<double> u_start(n);  // the last state that passed the guard
  for (int step = 1; step <= opt.load_steps; ++step) {
    if (opt.before_step) opt.before_step(step);
    u_start = u;
    data.s = static_cast<double>(step) / opt.load_steps;
    sample.load_step = step, sample.iteration = rep.iterations, sample.residual = 0.0, sample.step_converged = false;
    // Scale the residual by its size at the start of the step, so the tolerance is relative.
    system.residual(z.data(), data.s, R.data());
    double r0 = 0.0;
    for (const double r : R) r0 = std::max(r0, std::abs(r));
    N_VConst(r0 > 0.0 ? 1.0 / r0 : 1.0, fscale.get());
    const int flag = KINSol(kin.get(), y.get(), opt.line_search ? KIN_LINESEARCH : KIN_NONE, ones.get(), fscale.get());
    long iterations = 0;
    KINGetNumNonlinSolvIters(kin.get(), &iterations);
    rep.iterations += iterations;
    const detail::FactorState factored = factor_state(ls.get(), umfpack);
    if (factored.out_of_memory)
      throw SolveError(std::string("Newton: ") + factorizer + " ran out of memory factorizing the Jacobian (" +
                       std::to_string(A.col.size()) + " nonzeros before fill); use solver.type adr, "
                       "solver.linear_solver gamg (PETSc's multigrid: no factors), or a smaller horizon ratio "
                       "(the Jacobian couples particles two horizons apart)");
    // A singular tangent (a missing support, a mechanism): named by the condition number, an
    // estimate of ||J||_1 ||J^-1||_1 from a few solves with the last factors, beyond 1e13.
    // The pivot ratio min |U_ii| / max |U_ii| depends on the elimination order (a column past
    // its limit load: 7.6e-15 under one ordering, above the 1e-13 it was compared with under
    // another, where KINSOL then ran 2,219 iterations into a failed line search); the
    // condition number does not (4.1e2 by KLU's factors and UMFPACK's alike on the column's
    // elastic steps, 3.1e17 and 1.2e18 at its collapse). Estimated where the step did not end
    // cleanly, or its pivot ratio is below 1e-8 (a converged step in a body free to move).
    const bool clean = flag == KIN_SUCCESS || flag == KIN_INITIAL_GUESS_OK;
    const double condition = iterations > 0 && (!clean || factored.rcond < 1e-8) ? condition_number() : 0.0;
    if ((flag == KIN_LSETUP_FAIL && factored.singular) || condition > 1e13) {
      char factor[96];
      if (std::isinf(condition) || factored.singular)
        std::snprintf(factor, sizeof factor, "%s found a zero pivot", factorizer);
      else
        std::snprintf(factor, sizeof factor, "condition number %.1e, estimated from %s's factors", condition, factorizer);
      rep.failure = detail::singular_stiffness(model, step, factor);  // (an elastic body's throws: a missing support)
      std::copy(u_start.begin(), u_start.end(), u.begin());
      break;
    }
    // The residual as ADR measures it, for a like-for-like report.
    to_u();
    // The constrained dofs hold their imposed values exactly, not to the LU's rounding (a
    // pin read -6e-35 m once the multipliers were ordered last).
    loading.impose(data.s, u.data());
    system.residual(z.data(), data.s, R.data());
    R.resize(u.size());  // the constraint rows are not forces
    loading.zero_fixed(R.data());
    const double load = std::max(system.load_norm(u.data(), data.s), opt.load_floor);
    const double relative = load > 0.0 ? norm(R) / load : norm(R);
    if (!std::isfinite(relative) || !std::isfinite(norm(u))) {
      // The guard: a state or residual that is not finite is never kept, nor its row.
      std::copy(u_start.begin(), u_start.end(), u.begin());
      rep.diverged = true;
      rep.diverged_at = step;
      rep.failure = "Newton: the residual became NaN or Inf in load step " + std::to_string(step) +
                    " (KINSOL flag " + KINGetReturnFlagName(flag) + "); the last good state is load step " +
                    std::to_string(step - 1);
      break;
    }
    rep.residual = relative;
    rep.residual_force = norm(R);
    rep.stiffness_force = stiffness_force(u.size(), u.data(), [&A, &u](std::size_t k) {
      double sum = 0.0;  // over the displacement columns: not the multipliers'
      for (std::int64_t e = A.row_ptr[k]; e < A.row_ptr[k + 1]; ++e)
        if (A.col[e] < static_cast<std::int64_t>(u.size())) sum += std::abs(A.val[e]);
      return sum;
    });
    // Loads and reactions that are rounding themselves (a stress-free rigid motion): the
    // relative residual is rounding over rounding (3.1 on a translated bar) and the residual
    // force is measured against the rounding of the internal force instead.
    rep.at_rounding_floor = relative > opt.tolerance && rep.residual_force <= rounding_force(rep.stiffness_force);
    R.resize(n);
    rep.history.add({double(step), data.s, double(iterations), rep.residual});
    if (loading.has_supports()) detail::append_reactions(model, loading, data.s, u.data(), fint, reactions, rep.history);
    if (progress) {
      sample.iteration = rep.iterations, sample.residual = rep.residual, sample.step_converged = true;
      progress->update(sample);
    }
    // A stalled line search is accepted where the run's own measure (ADR's relative residual,
    // reported) meets the tolerance: KINSOL tests the largest entry over the step's first
    // one, which rounding can hold above it (the plane-strain cantilever at nu = 0.499,
    // 16 particles thick: 2.1e-11 against 1e-10, KINSOL stopped).
    const bool ok = flag == KIN_SUCCESS || flag == KIN_INITIAL_GUESS_OK ||
                    (flag == KIN_STEP_LT_STPTOL && rep.residual < 1e-6) ||
                    (flag == KIN_LINESEARCH_NONCONV && rep.residual <= opt.tolerance);
    if (!ok) {
      char at[160];
      std::snprintf(at, sizeof at, " at a residual of %.3e (solver.tolerance %.1e)", rep.residual, opt.tolerance);
      rep.failure = "Newton: KINSOL stopped in load step " + std::to_string(step) + " with flag " +
                    std::to_string(flag) + " (" + KINGetReturnFlagName(flag) + ")" + at;
      // A line search that stalls above the tolerance: the residual at its rounding floor.
      if (flag == KIN_LINESEARCH_NONCONV)
        rep.failure += ": no step along Newton's direction lowers the residual, which near the tolerance is rounding in "
                       "a badly conditioned stiffness (a nearly incompressible material: nu near 1/2); a looser "
                       "solver.tolerance, or solver.type: direct for a linear problem (it refines on its factor)";
      break;
    }
    if (opt.after_step) opt.after_step(step, u, iterations, rep.residual);
  }
  rep.converged = rep.failure.empty();
  if (progress) progress->finish();
  return rep;
}

}  // namespace perinom

// Newton's method through PETSc SNES on the Galerkin-reduced static problem, with MUMPS or
// GAMG for the linear steps (newton.hpp, NewtonOptions::linear_solver). Part of the PETSc
// module libperinom_petsc.so (petsc_plugin.hpp), which libperinom loads on first use.
#include <petscsnes.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <memory>
#include <utility>

#include <Eigen/Dense>

#include "galerkin.hpp"
#include "mumps_memory.hpp"
#include "petsc_reduced.hpp"
#include "petsc_rigid_null.hpp"
#include "perinom/core/error.hpp"
#include "perinom/core/memory.hpp"
#include "perinom/solvers/newton.hpp"
#include "perinom/solvers/rounding_force.hpp"
#include "petsc_partition.hpp"
#include "petsc_plugin.hpp"
#include "petsc_ranks.hpp"
#include "petsc_session.hpp"
#include "singular_stiffness.hpp"

namespace perinom::detail {
namespace {

PetscErrorCode residual_callback(SNES snes, Vec x, Vec r, void* ctx) {
  auto* sys = static_cast<Reduced*>(ctx);
  const PetscScalar* xa = nullptr;
  PetscScalar* ra = nullptr;
  PetscErrorCode e = VecGetArrayRead(x, &xa);
  if (!e) e = VecGetArray(r, &ra);
  if (e) return e;
  try {
    sys->residual(xa, ra);
  } catch (...) {
    sys->error = std::current_exception();
  }
  int finite = 1;
  for (PetscInt k = 0; k < sys->free(); ++k) finite = finite && std::isfinite(ra[k]);
  VecRestoreArray(r, &ra);
  VecRestoreArrayRead(x, &xa);
  if (sys->error) return PETSC_ERR_USER;
  if (sys->E.p) {
    // The multiplier form: R += [E^T lambda; E u] (every rank has E), in place.
    e = MatMultAdd(sys->E.p, x, r, r);
    if (e) return e;
  }
  MPI_Allreduce(MPI_IN_PLACE, &finite, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);  // every rank takes one branch
  // A state whose force is not finite: SNES's line search steps back, or the solve stops.
  return finite ? 0 : SNESSetFunctionDomainError(snes);
}

/// perinom's own stages in PETSc's -log_view: K_T from the tangent rows, and its copy into
/// the Mat.
struct Events {
  PetscLogEvent assemble = 0, copy = 0;
  Events() {
    PetscClassId id = 0;
    PetscClassIdRegister("perinom", &id);
    PetscLogEventRegister("perinomKT", id, &assemble);
    PetscLogEventRegister("perinomKTtoMat", id, &copy);
  }
};

/// The Jacobian callback's context: the system, and what runs once on the first Jacobian
/// before anything factors it (empty: nothing).
struct JacobianContext {
  Reduced* sys;
  std::function<void(Mat)> first;
};

PetscErrorCode jacobian_callback(SNES, Vec x, Mat J, Mat, void* ctx) {
  static const Events events;
  auto* context = static_cast<JacobianContext*>(ctx);
  Reduced* sys = context->sys;
  const PetscScalar* xa = nullptr;
  PetscErrorCode e = VecGetArrayRead(x, &xa);
  if (e) return e;
  PetscLogEventBegin(events.assemble, 0, 0, 0, 0);
  RowSparse A;
  try {
    A = sys->jacobian(xa);
  } catch (...) {
    sys->error = std::current_exception();
  }
  PetscLogEventEnd(events.assemble, 0, 0, 0, 0);
  VecRestoreArrayRead(x, &xa);
  if (sys->error) return PETSC_ERR_USER;
  PetscLogEventBegin(events.copy, 0, 0, 0, 0);
  const PetscInt* ptr = A.outerIndexPtr();
  const PetscInt first = sys->first, end = sys->first + sys->free();  // this rank's rows, globally
  if (!sys->assembled) {
    // The pattern: the tangent rows' (fixed for the run), preallocated exactly: the columns
    // of this rank's rows (its diagonal block), and the others'. (The multiplier form's E^T
    // entries that other ranks add to these rows are allocated as they come.)
    std::vector<PetscInt> own(static_cast<std::size_t>(sys->free()), 0), other(own.size(), 0);
    auto count = [&](PetscInt r, PetscInt c) { ++(c >= first && c < end ? own : other)[static_cast<std::size_t>(r)]; };
    for (PetscInt r = 0; r < A.rows(); ++r)
      for (PetscInt k = ptr[r]; k < ptr[r + 1]; ++k) count(r, A.innerIndexPtr()[k]);
    for (std::size_t k = 0; k < sys->e_row.size(); ++k)
      if (sys->e_row[k] >= first && sys->e_row[k] < end) count(sys->e_row[k] - first, sys->e_col[k]);
    e = MatXAIJSetPreallocation(J, 1, own.data(), other.data(), nullptr, nullptr);
    if (!e) e = MatSetOption(J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE);
    if (e) return e;
    sys->assembled = true;
  } else if ((e = MatZeroEntries(J))) {
    return e;
  }
  for (PetscInt r = 0; r < A.rows() && !e; ++r) {
    const PetscInt row = first + r;
    e = MatSetValues(J, 1, &row, ptr[r + 1] - ptr[r], A.innerIndexPtr() + ptr[r], A.valuePtr() + ptr[r], ADD_VALUES);
  }
  if (!e) e = sys->add_constraints(J);
  if (!e) e = MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY);
  if (!e) e = MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY);
  PetscLogEventEnd(events.copy, 0, 0, 0, 0);
  if (!e && context->first) {
    try {
      std::exchange(context->first, nullptr)(J);
    } catch (...) {
      sys->error = std::current_exception();
      return PETSC_ERR_USER;
    }
  }
  return e;
}

/// The rigid-body modes of a solid over every dof: d translations, then the rotations
/// (one in 2-D, three in 3-D) about the origin; empty when positions are not given or the
/// model is not a solid (dofs per particle != dimension).
std::vector<Eigen::VectorXd> rigid_body_modes(const NewtonOptions& opt, const TangentModel& model) {
  const int d = opt.dimension;
  if (opt.positions.empty() || d != model.dofs_per_particle() || opt.positions.size() != model.particles() * d)
    return {};
  const Eigen::Index n = static_cast<Eigen::Index>(model.dofs());
  std::vector<Eigen::VectorXd> modes(d == 2 ? 3 : 6, Eigen::VectorXd::Zero(n));
  for (std::size_t i = 0; i < model.particles(); ++i) {
    const double* x = &opt.positions[i * d];
    const Eigen::Index k = static_cast<Eigen::Index>(i * d);
    for (int a = 0; a < d; ++a) modes[a][k + a] = 1.0;
    if (d == 2) {
      modes[2][k] = -x[1], modes[2][k + 1] = x[0];
    } else {
      modes[3][k + 1] = -x[2], modes[3][k + 2] = x[1];  // about x
      modes[4][k] = x[2], modes[4][k + 2] = -x[0];      // about y
      modes[5][k] = -x[1], modes[5][k + 1] = x[0];      // about z
    }
  }
  return modes;
}

/// GAMG's near-null space in reduced coordinates (each mode's free entries), made orthonormal
/// over the ranks (Gram-Schmidt, twice); a mode the supports leave (almost) nothing of is
/// dropped.
void set_near_null_space(Mat J, const Reduced& sys, const std::vector<Eigen::VectorXd>& modes) {
  if (modes.empty()) return;
  std::vector<Vec> vecs;
  for (const Eigen::VectorXd& mode : modes) {
    Vec v = nullptr;
    check(MatCreateVecs(J, &v, nullptr), "MatCreateVecs");
    PetscScalar* a = nullptr;
    check(VecGetArray(v, &a), "VecGetArray");
    // T is the identity on the free dofs: a column's unit entry is its own dof.
    for (Eigen::Index col = 0; col < sys.T.cols(); ++col)
      for (Sparse::InnerIterator it(sys.T, col); it; ++it)
        if (it.value() == 1.0) a[col] = mode[it.row()];
    check(VecRestoreArray(v, &a), "VecRestoreArray");
    PetscReal before = 0.0, after = 0.0;
    check(VecNorm(v, NORM_2, &before), "VecNorm");
    for (int pass = 0; pass < 2; ++pass)
      for (Vec q : vecs) {
        PetscScalar along = 0.0;
        check(VecDot(v, q, &along), "VecDot");
        check(VecAXPY(v, -along, q), "VecAXPY");
      }
    check(VecNormalize(v, &after), "VecNormalize");
    if (after > 1e-8 * before) vecs.push_back(v);
    else VecDestroy(&v);
  }
  if (vecs.empty()) return;
  MatNullSpace space = nullptr;
  check(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(vecs.size()), vecs.data(), &space),
        "MatNullSpaceCreate");
  check(MatSetNearNullSpace(J, space), "MatSetNearNullSpace");
  MatNullSpaceDestroy(&space);
  for (Vec& v : vecs) VecDestroy(&v);
}

/// The linear solver of each step: perinom's choice, then the user's PETSc options over it.
void configure(SNES snes, Mat J, const Reduced& sys, const NewtonOptions& opt) {
  KSP ksp = nullptr;
  PC pc = nullptr;
  check(SNESGetKSP(snes, &ksp), "SNESGetKSP");
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  // Elastic models (the consistent and classical formulations, the plate) have a symmetric
  // tangent, plastic ones not.
  const bool symmetric = !sys.model.history();
  if (opt.linear_solver == "mumps") {
    // Symmetric: MUMPS's LDL^T (half the work of LU). Told only "symmetric", not "positive
    // definite": MUMPS's Cholesky (SYM = 1) took as long on the 101k-particle plate and does
    // not detect null pivots, so a body free to move went unnamed.
    if (symmetric) check(MatSetOption(J, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
    check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
    check(PCSetType(pc, symmetric ? PCCHOLESKY : PCLU), "PCSetType");
    check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
    // Null pivot detection (ICNTL(24)), so a singular stiffness is named as such (INFOG(28))
    // rather than met as a Newton step that never converges.
    PetscBool given = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, "-mat_mumps_icntl_24", &given), "PetscOptionsHasName");
    if (!given) check(PetscOptionsSetValue(nullptr, "-mat_mumps_icntl_24", "1"), "PetscOptionsSetValue");
  } else if (opt.linear_solver == "gamg" && sys.E.p) {
    throw InputError("solver.linear_solver: gamg takes constraints on their particles only over MPI ranks (a face-"
                     "located support, at: face, makes Newton's system a saddle point there): use mumps");
  } else if (opt.linear_solver == "gamg") {
    // Conjugate gradients for a symmetric tangent, GMRES otherwise. Each linear solve goes
    // a decade below the Newton tolerance, so an elastic step needs one Newton iteration.
    // Symmetric and, the supports holding every rigid mode, positive definite: told so,
    // GAMG estimates its smoothers' eigenvalues by conjugate gradients (told only
    // "symmetric", its set-up on the 101k-particle plate took 8.8 s instead of 2.1-6.6 s).
    if (symmetric) check(MatSetOption(J, MAT_SPD, PETSC_TRUE), "MatSetOption");
    check(KSPSetType(ksp, symmetric ? KSPCG : KSPGMRES), "KSPSetType");
    // The tolerance on the true residual (CG's own norm, GMRES preconditioned on the right),
    // not on the preconditioned one, which can be far smaller.
    if (symmetric) check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
    else check(KSPSetPCSide(ksp, PC_RIGHT), "KSPSetPCSide");
    check(PCSetType(pc, PCGAMG), "PCSetType");
    check(KSPSetTolerances(ksp, std::max(0.1 * opt.tolerance, 1e-14), PETSC_DEFAULT, PETSC_DEFAULT, 10000),
          "KSPSetTolerances");
    set_near_null_space(J, sys, rigid_body_modes(opt, sys.model));
  } else {
    throw InputError("solver.linear_solver: must be klu, umfpack, mumps or gamg (got " + opt.linear_solver + ")");
  }
  SNESLineSearch ls = nullptr;
  check(SNESGetLineSearch(snes, &ls), "SNESGetLineSearch");
  check(SNESLineSearchSetType(ls, opt.line_search ? SNESLINESEARCHBT : SNESLINESEARCHBASIC), "SNESLineSearchSetType");
  check(SNESSetTolerances(snes, 0.0, opt.tolerance, opt.step_tolerance, opt.max_iterations, -1), "SNESSetTolerances");
  // Every rank reads the same options (one --petsc-options): a bad one fails on every rank
  // alike, and is said once (it was printed by each rank).
  try {
    check(SNESSetFromOptions(snes), "SNESSetFromOptions");
  } catch (const SolveError& e) {
    throw SolveErrorOnEveryRank(e.what());
  }
}

/// The MUMPS factor of the last linear solve, or nullptr (another solver, or none yet).
Mat mumps_factor(SNES snes, const NewtonOptions& opt) {
  if (opt.linear_solver != "mumps") return nullptr;
  KSP ksp = nullptr;
  PC pc = nullptr;
  Mat F = nullptr;
  if (SNESGetKSP(snes, &ksp) || KSPGetPC(ksp, &pc) || PCFactorGetMatrix(pc, &F)) return nullptr;
  return F;
}

/// MUMPS's INFOG(1) after the last factorization (0: fine, or not MUMPS).
PetscInt mumps_status(SNES snes, const NewtonOptions& opt) {
  PetscInt status = 0;
  const Mat F = mumps_factor(snes, opt);
  return F && !MatMumpsGetInfog(F, 1, &status) ? status : 0;
}

/// How many times a load step factors again after MUMPS ran out of workspace.
constexpr int kWidenings = 3;

/// When MUMPS's last factorization ran out of workspace (INFOG(1) -8, -9, -14, -17 or -20:
/// its analysis's estimate leaves out the pivots it delays, which a saddle point's zero block
/// makes: a 3-D block held at: face failed so on 2 and 3 ranks at the default 20%, solved at
/// 40%), doubles ICNTL(14), the room added to the estimate, and drops the factor, so that the
/// next linear solve analyses and factors anew with it (a failed factor is not factored again
/// in place); returns the new room, or 0 for another failure.
PetscInt widen_mumps_workspace(SNES snes, const NewtonOptions& opt) {
  const PetscInt status = mumps_status(snes, opt);
  if (status != -8 && status != -9 && status != -14 && status != -17 && status != -20) return 0;
  PetscInt room = 0;
  check(MatMumpsGetIcntl(mumps_factor(snes, opt), 14, &room), "MatMumpsGetIcntl");
  room = std::max<PetscInt>(2 * room, 20);
  check(PetscOptionsSetValue(nullptr, "-mat_mumps_icntl_14", std::to_string(room).c_str()), "PetscOptionsSetValue");
  KSP ksp = nullptr;
  check(SNESGetKSP(snes, &ksp), "SNESGetKSP");
  check(KSPReset(ksp), "KSPReset");
  return room;
}

/// MUMPS's count of null pivots in the last factorization, or -1 when it stopped on a
/// numerically singular matrix (INFOG(1) = -10, as a Cholesky of one does); 0 otherwise and
/// for another solver.
PetscInt null_pivots(SNES snes, const NewtonOptions& opt) {
  const Mat F = mumps_factor(snes, opt);
  PetscInt count = 0;
  if (!F) return 0;
  if (mumps_status(snes, opt) == -10) return -1;
  return MatMumpsGetInfog(F, 28, &count) ? 0 : count;
}

SolveReport solve(TangentModel& model, const Loading& loading, const NewtonOptions& opt, std::vector<double>& u,
                  Progress* progress, const std::string& petsc_options) {
  if (loading.collocated)
    throw InputError("solver.linear_solver: " + opt.linear_solver +
                     " solves the Galerkin-reduced system, and the improved and strong formulations collocate their "
                     "constraints; use linear_solver umfpack or klu");
  start_petsc(petsc_options);
  u.resize(model.dofs(), 0.0);
  Reduced sys(model, loading);
  SolveReport rep;
  rep.history.columns = {"load_step", "load_factor", "newton_iterations", "residual", "linear_iterations"};
  const int dpp = model.dofs_per_particle();
  for (const auto& c : loading.reaction_columns(dpp)) rep.history.columns.push_back(c);
  std::vector<double> reactions(loading.support_names.size() * dpp);

  Owned<Vec, VecDestroy> x, r;
  Owned<Mat, MatDestroy> J;
  Owned<SNES, SNESDestroy> snes;
  const PetscInt n = sys.free();
  check(VecCreateMPI(PETSC_COMM_WORLD, n, PETSC_DETERMINE, &x.p), "VecCreateMPI");
  check(VecDuplicate(x.p, &r.p), "VecDuplicate");
  check(MatCreate(PETSC_COMM_WORLD, &J.p), "MatCreate");
  check(MatSetSizes(J.p, n, n, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(J.p, MATAIJ), "MatSetType");
  check(SNESCreate(PETSC_COMM_WORLD, &snes.p), "SNESCreate");
  check(SNESSetFunction(snes.p, r.p, residual_callback, &sys), "SNESSetFunction");
  JacobianContext jacobian{&sys, nullptr};
  if (opt.linear_solver == "mumps")
    // MUMPS's own analysis of the first Jacobian says its factors' size before they are made
    // (mumps_memory.hpp); the factorization then uses that analysis.
    jacobian.first = [&](Mat first) {
      KSP ksp = nullptr;
      PC pc = nullptr;
      check(SNESGetKSP(snes.p, &ksp), "SNESGetKSP");
      check(KSPGetPC(ksp, &pc), "KSPGetPC");
      const MumpsPrediction factors = analyse_mumps_factors(pc, first, !model.history());
      if (factors.largest_bytes <= 0.0) return;  // (a preconditioner of the user's own)
      if (progress) {
        char what[240];
        std::snprintf(what, sizeof what,
                      "Newton: MUMPS's factors, by its analysis (%.1f s): %.0f MiB on the largest process, %.0f MiB on all, "
                      "beside the %.0f MiB this process holds",
                      factors.seconds, factors.largest_bytes / 1048576.0, factors.total_bytes / 1048576.0,
                      resident_bytes() / 1048576.0);
        progress->phase(what);
      }
      PetscInt unknowns = 0;
      check(MatGetSize(first, &unknowns, nullptr), "MatGetSize");
      require_mumps_memory(factors, unknowns, opt.memory_limit);
    };
  check(SNESSetJacobian(snes.p, J.p, J.p, jacobian_callback, &jacobian), "SNESSetJacobian");
  configure(snes.p, J.p, sys, opt);
  {
    // The first guess: u's free entries (T is the identity on them).
    PetscScalar* a = nullptr;
    check(VecSet(x.p, 0.0), "VecSet");  // (the multipliers start at zero)
    check(VecGetArray(x.p, &a), "VecGetArray");
    for (Eigen::Index col = 0; col < sys.T.cols(); ++col)
      for (Sparse::InnerIterator it(sys.T, col); it; ++it)
        if (it.value() == 1.0) a[col] = u[static_cast<std::size_t>(it.row())];
    check(VecRestoreArray(x.p, &a), "VecRestoreArray");
  }

  ProgressSample sample;
  sample.limit = 0;
  sample.load_steps = opt.load_steps;
  std::vector<double> fint(model.dofs());
  const std::vector<double> row_sums = model.stiffness_row_sums();  // for the rounding floor
  Owned<Vec, VecDestroy> x_start;
  check(VecDuplicate(x.p, &x_start.p), "VecDuplicate");
  for (int step = 1; step <= opt.load_steps; ++step) {
    check(VecCopy(x.p, x_start.p), "VecCopy");
    sys.s = static_cast<double>(step) / opt.load_steps;
    PetscInt iterations = 0, linear = 0;
    SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
    for (int widened = 0;; ++widened) {
      if (opt.before_step) opt.before_step(step);
      const PetscErrorCode solved = SNESSolve(snes.p, nullptr, x.p);
      if (sys.error) std::rethrow_exception(sys.error);
      check(solved, "SNESSolve");
      SNESGetIterationNumber(snes.p, &iterations);
      SNESGetLinearSolveIterations(snes.p, &linear);
      SNESGetConvergedReason(snes.p, &reason);
      rep.iterations += iterations;
      if (reason != SNES_DIVERGED_LINEAR_SOLVE || widened == kWidenings) break;
      const PetscInt room = widen_mumps_workspace(snes.p, opt);
      if (room == 0) break;
      if (progress) {
        char what[200];
        std::snprintf(what, sizeof what, "Newton: MUMPS ran out of workspace in load step %d; factoring again with "
                      "ICNTL(14) = %d%% added to its estimate", step, static_cast<int>(room));
        progress->phase(what);
      }
      check(VecCopy(x_start.p, x.p), "VecCopy");
    }
    if (const PetscInt nulls = null_pivots(snes.p, opt); nulls != 0) {
      // (An elastic body's singular stiffness throws: a missing support.)
      rep.failure = singular_stiffness(model, step, nulls > 0 ? "MUMPS found " + std::to_string(nulls) + " null pivots"
                                                              : std::string("MUMPS stopped: numerically singular"));
      check(VecCopy(x_start.p, x.p), "VecCopy");
      break;
    }
    // GAMG's conjugate gradients on a stiffness a free rigid motion makes singular stop as
    // indefinite or converge, by rounding: serially a bar free along y converged with an
    // arbitrary y translation, over 2 ranks it stopped. Asked of the matrix instead, the
    // weakest rigid motion against the strongest held one (a fixed cut on the weakest alone,
    // 1e-7 of ||J||, fell towards held bodies' values as they grew: 2.5e-4 at 600 particles,
    // as N^-1/2).
    if (opt.linear_solver == "gamg") {
      if (const RigidNull null = rigid_null_measure(J.p); null.free()) {
        char force[160], what[600];
        if (null.largest < 1e-12)  // every rigid motion free: a ratio of two rounding values says nothing
          std::snprintf(force, sizeof force, "every rigid motion meets a force of %.1e of the stiffness's scale",
                        null.largest);
        else
          std::snprintf(force, sizeof force, "a rigid motion the supports leave free meets a force of %.1e of the "
                        "most held one's", null.smallest / null.largest);
        std::snprintf(what, sizeof what, "Newton (PETSc): the linear solver gamg failed in load step %d: a singular "
                      "stiffness (%s: e.g. a missing boundary condition, which run warns of before the solve); the "
                      "last good state is load step %d", step, force, step - 1);
        rep.failure = what;
        check(VecCopy(x_start.p, x.p), "VecCopy");
        break;
      }
    }
    if (reason < 0) {
      // The iterate SNES stopped at is no balanced state (a free body's was 1.3e8 m off):
      // the last step's state stays, as for a singular factor.
      rep.failure = "Newton (PETSc): SNES stopped in load step " + std::to_string(step) + " with " +
                    SNESConvergedReasons[reason] + "; the last good state is load step " + std::to_string(step - 1);
      if (reason == SNES_DIVERGED_LINEAR_SOLVE && mumps_status(snes.p, opt) < 0)
        rep.failure += " (MUMPS stopped with INFOG(1) = " + std::to_string(mumps_status(snes.p, opt)) +
                       "; for a workspace too small, -8, -9, -14, -17 or -20, raise -mat_mumps_icntl_14)";
      else if (reason == SNES_DIVERGED_LINEAR_SOLVE)
        rep.failure += " (the linear solver " + opt.linear_solver +
                       " failed: a singular stiffness, e.g. a missing boundary condition, or -ksp_max_it too low)";
      else if (!model.history())
        rep.failure += " (a linear elastic body: a stiffness singular to rounding, e.g. a rigid motion the supports "
                       "leave free, which run warns of before the solve)";
      if (reason == SNES_DIVERGED_FNORM_NAN) rep.diverged = true, rep.diverged_at = step;
      check(VecCopy(x_start.p, x.p), "VecCopy");
      break;
    }
    // The residual as ADR measures it (as the UMFPACK and KLU path reports it).
    {
      const PetscScalar* a = nullptr;
      check(VecGetArrayRead(x.p, &a), "VecGetArrayRead");
      sys.expand(a);
      check(VecRestoreArrayRead(x.p, &a), "VecRestoreArrayRead");
    }
    sys.force();
    Eigen::VectorXd R = sys.T.transpose() * sys.f;
    if (sys.E.p) {
      // The multiplier form: the balance with the constraints' forces E^T lambda.
      check(MatMult(sys.E.p, x.p, r.p), "MatMult");
      const PetscScalar* a = nullptr;
      check(VecGetArrayRead(r.p, &a), "VecGetArrayRead");
      R += Eigen::Map<const Eigen::VectorXd>(a, R.size());
      check(VecRestoreArrayRead(r.p, &a), "VecRestoreArrayRead");
    }
    // Squared norms of the residual, the reactions, the applied force, u and the stiffness
    // force (rounding_force.hpp), over the ranks.
    double sums[5] = {R.squaredNorm(), 0.0, loading.force_norm(sys.s), sys.u.squaredNorm(),
                      stiffness_force(row_sums.size(), sys.u.data(), [&row_sums](std::size_t k) { return row_sums[k]; })};
    sums[2] *= sums[2], sums[4] *= sums[4];
    for (const auto dof : loading.fixed) {
      const double fi = sys.f[static_cast<Eigen::Index>(dof)] + loading.force_at(sys.s, static_cast<std::size_t>(dof));
      sums[1] += fi * fi;
    }
    model.sum_across_ranks(sums, 5);
    const double load = std::max(std::sqrt(std::max(sums[2], sums[1])), opt.load_floor);
    const double relative = load > 0.0 ? std::sqrt(sums[0]) / load : std::sqrt(sums[0]);
    if (!std::isfinite(relative) || !std::isfinite(sums[3])) {
      check(VecCopy(x_start.p, x.p), "VecCopy");
      rep.diverged = true;
      rep.diverged_at = step;
      rep.failure = "Newton (PETSc): the residual became NaN or Inf in load step " + std::to_string(step) +
                    " (SNES reason " + SNESConvergedReasons[reason] + "); the last good state is load step " +
                    std::to_string(step - 1);
      break;
    }
    std::copy(sys.u.data(), sys.u.data() + sys.u.size(), u.begin());
    rep.residual = relative;
    rep.residual_force = std::sqrt(sums[0]), rep.stiffness_force = std::sqrt(sums[4]);
    // Loads and reactions that are rounding themselves: as the serial path (newton.cpp).
    rep.at_rounding_floor = relative > opt.tolerance && rep.residual_force <= rounding_force(rep.stiffness_force);
    rep.history.add({double(step), sys.s, double(iterations), relative, double(linear)});
    if (loading.has_supports()) append_reactions(model, loading, sys.s, u.data(), fint, reactions, rep.history);
    if (progress) {
      sample.iteration = rep.iterations, sample.load_step = step, sample.residual = relative;
      sample.step_converged = true;
      progress->update(sample);
    }
    if (opt.after_step) opt.after_step(step, u, iterations, relative);
  }
  rep.converged = rep.failure.empty();
  if (progress) progress->finish();
  return rep;
}

}  // namespace
}  // namespace perinom::detail

extern "C" const perinom::detail::PetscPlugin* perinom_petsc_plugin() {
  using namespace perinom::detail;
  static const PetscPlugin plugin{solve,        end_petsc,          world,  halo_create, halo_update, halo_add_to_owners,
                                  halo_destroy, reduce,             gather, barrier,     abort_ranks,
                                  partition_graph};
  return &plugin;
}

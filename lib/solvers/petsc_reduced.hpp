#pragma once
/// @file Newton's static problem as PETSc SNES sees it (newton_petsc.cpp), on one process or
/// over MPI ranks. Internal to the PETSc module (lib/solvers).
#include <petscmat.h>

#include <exception>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "galerkin.hpp"

namespace perinom::detail {

static_assert(sizeof(PetscInt) == sizeof(int), "PETSc with 32-bit indices (RowSparse's)");

/// A PETSc object released by its own destroy function.
template <class T, PetscErrorCode (*destroy)(T*)>
struct Owned {
  T p = nullptr;
  ~Owned() {
    if (p) destroy(&p);
  }
};

/// The reduced problem: u = T x + p(s) with x the free dofs, R(x) = T^T (f_int(u) - f_ext(s)),
/// J(x) = T^T K(u) T. The prescribed part is affine in s (targets value0 + s value). Over MPI
/// ranks (a DistributedModel) x, u and f are this rank's own dofs, and J's rows too, its
/// columns numbered globally.
/// Over ranks with face-located constraints, whose T would read other ranks' dofs, the
/// multiplier form instead: x = (u, lambda) over the own dofs and constraints,
/// R = (f_int(u) - f_ext(s) + E^T lambda, E u - t(s)), J = [K E^T; E 0], E's row of
/// constraint k being u_F / scale_k + sum_c coef_c u_c (Loading) times a stiffness k_E (the
/// mean of K's row sums), so that its rows weigh as much as the force rows in SNES's norms (in
/// metres, a step's constraint rows start near 1e-6 against forces balanced to rounding, and
/// SNES's relative decrease cannot be met: the plastic plate's line search failed so). Both
/// forms have the same u (E T = 0); the second is a saddle point, for MUMPS.
struct Reduced {
  TangentModel& model;
  const Loading& loading;
  Sparse T;
  std::unique_ptr<TRows> rows;  // T by rows, for K_T's assembly
  Eigen::VectorXd p0, dp;  // p(s) = p0 + s dp
  double s = 0.0;
  Eigen::VectorXd u, f;
  bool assembled = false;  // the Jacobian's pattern is in the Mat
  // Over more than one rank: this rank's first free number in the global numbering, and each
  // column dof's global free number (own dofs, then ghosts; -1 for a constrained one).
  bool spread = false;
  PetscInt first = 0, global = 0;
  std::vector<int> column;
  // The multiplier form: the constraints' count (0 in the reduced form) and E, E^T as global
  // (row, column, value) entries, and as a Mat (null in the reduced form).
  PetscInt lambdas = 0;
  double k_E = 1.0;
  std::vector<PetscInt> e_row, e_col;
  std::vector<double> e_value;
  Owned<Mat, MatDestroy> E;
  /// What a callback threw (an exception must not cross PETSc's C frames): SNESSolve then
  /// returns an error, and the solve rethrows this instead.
  std::exception_ptr error;

  /// Collective over PETSC_COMM_WORLD (PETSc started).
  Reduced(TangentModel& m, const Loading& l);
  /// Unknowns on this rank: free dofs, plus the multipliers.
  PetscInt free() const { return static_cast<PetscInt>(T.cols()) + lambdas; }
  /// u from x.
  void expand(const double* x);
  /// f = f_int(u) - f_ext(s) over every dof (u expanded already).
  void force();
  /// R without the multiplier form's E x (residual_callback adds it).
  void residual(const double* x, double* R);
  /// J's rows of the free dofs (global columns over ranks), at x; without E.
  RowSparse jacobian(const double* x);
  /// Adds E and E^T to A (rows of other ranks included; before A's assembly).
  PetscErrorCode add_constraints(Mat A) const;

 private:
  /// Whether any rank has face-located constraints (collective): over ranks they read other
  /// ranks' dofs, so the multiplier form.
  bool any_couplings() const;
  /// first, global and column: the global numbers (collective; `own` unknowns here).
  void number_columns(const std::vector<std::int64_t>& index, PetscInt own);
  /// k_E, E and E^T of this rank's constraints in the global numbering (collective: E's Mat).
  void constraint_rows();
};

}  // namespace perinom::detail

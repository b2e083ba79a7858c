// The UMFPACK linear solver KINSOL runs Newton's steps with (solver.linear_solver umfpack):
// it is handed the Jacobian in CSR and factors it read as CSC, that is the transpose, so a
// non-symmetric matrix is where a mix-up of A and A^T would show. Also: a new pattern gets a
// new symbolic analysis, and a singular matrix is reported, not solved.
#include <catch2/catch.hpp>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <cmath>
#include <vector>

#include "../../lib/solvers/umfpack_linear_solver.hpp"

using namespace perinom;

namespace {

/// A CSR matrix of n rows from dense row-major values (zeros left out of the pattern).
SUNMatrix csr(SUNContext ctx, int n, const std::vector<double>& dense) {
  int nnz = 0;
  for (const double v : dense) nnz += v != 0.0;
  SUNMatrix A = SUNSparseMatrix(n, n, nnz, CSR_MAT, ctx);
  sunindextype k = 0;
  for (int i = 0; i < n; ++i) {
    SM_INDEXPTRS_S(A)[i] = k;
    for (int j = 0; j < n; ++j)
      if (dense[i * n + j] != 0.0) SM_INDEXVALS_S(A)[k] = j, SM_DATA_S(A)[k++] = dense[i * n + j];
  }
  SM_INDEXPTRS_S(A)[n] = k;
  return A;
}

/// max_i |(A x - b)_i| for the dense A.
double residual(int n, const std::vector<double>& dense, const double* x, const double* b) {
  double r = 0.0;
  for (int i = 0; i < n; ++i) {
    double s = -b[i];
    for (int j = 0; j < n; ++j) s += dense[i * n + j] * x[j];
    r = std::max(r, std::abs(s));
  }
  return r;
}

}  // namespace

TEST_CASE("UMFPACK solves the non-symmetric CSR system it is given, refactors, and reports a singular one",
          "[solvers][newton]") {
  SUNContext ctx = nullptr;
  REQUIRE(SUNContext_Create(nullptr, &ctx) == 0);
  const int n = 4;
  N_Vector x = N_VNew_Serial(n, ctx), b = N_VNew_Serial(n, ctx);
  for (int i = 0; i < n; ++i) N_VGetArrayPointer(b)[i] = 1.0 + i;
  SUNLinearSolver ls = detail::umfpack_linear_solver(ctx);
  REQUIRE(ls != nullptr);
  CHECK(SUNLinSolGetType(ls) == SUNLINEARSOLVER_DIRECT);
  // Far from symmetric: solving A^T x = b instead would leave a residual of order 1.
  const std::vector<double> a = {4, 3, 0, 0,   //
                                 0, 5, 2, 0,   //
                                 1, 0, 6, 7,   //
                                 0, 0, 0, 8};
  SUNMatrix A = csr(ctx, n, a);
  REQUIRE(SUNLinSolSetup(ls, A) == SUNLS_SUCCESS);
  REQUIRE(SUNLinSolSolve(ls, A, x, b, 0.0) == SUNLS_SUCCESS);
  CHECK(residual(n, a, N_VGetArrayPointer(x), N_VGetArrayPointer(b)) < 1e-14);
  const detail::FactorState first = detail::umfpack_factor_state(ls);
  CHECK_FALSE(first.singular);
  CHECK(first.rcond > 0.1);
  // The same pattern with new values (the symbolic analysis kept), then a new pattern.
  std::vector<double> a2 = a;
  for (double& v : a2) v *= v != 0.0 ? 1.5 : 0.0;
  a2[0] = -2.0;
  SUNMatrix A2 = csr(ctx, n, a2);
  REQUIRE(SUNLinSolSetup(ls, A2) == SUNLS_SUCCESS);
  REQUIRE(SUNLinSolSolve(ls, A2, x, b, 0.0) == SUNLS_SUCCESS);
  CHECK(residual(n, a2, N_VGetArrayPointer(x), N_VGetArrayPointer(b)) < 1e-14);
  std::vector<double> a3 = a;
  a3[3] = 9.0, a3[12] = -1.0;
  SUNMatrix A3 = csr(ctx, n, a3);
  REQUIRE(SUNLinSolSetup(ls, A3) == SUNLS_SUCCESS);
  REQUIRE(SUNLinSolSolve(ls, A3, x, b, 0.0) == SUNLS_SUCCESS);
  CHECK(residual(n, a3, N_VGetArrayPointer(x), N_VGetArrayPointer(b)) < 1e-14);
  // x and b the same storage (UMFPACK needs them apart; the solver copies b).
  N_VScale(1.0, b, x);
  REQUIRE(SUNLinSolSolve(ls, A3, x, x, 0.0) == SUNLS_SUCCESS);
  CHECK(residual(n, a3, N_VGetArrayPointer(x), N_VGetArrayPointer(b)) < 1e-14);
  // A zero row: singular. Setup fails recoverably (KINSOL stops with KIN_LSETUP_FAIL) and says why.
  std::vector<double> s = a;
  s[15] = 0.0;  // row 3's only entry: the row is empty
  SUNMatrix S = csr(ctx, n, s);
  CHECK(SUNLinSolSetup(ls, S) > 0);
  CHECK(detail::umfpack_factor_state(ls).singular);
  CHECK(SUNLinSolSolve(ls, S, x, b, 0.0) < 0);
  for (SUNMatrix m : {A, A2, A3, S}) SUNMatDestroy(m);
  SUNLinSolFree(ls);
  N_VDestroy(x), N_VDestroy(b);
  SUNContext_Free(&ctx);
}

#include "umfpack_linear_solver.hpp"

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <umfpack.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "condition_estimate.hpp"

#include "fill_ordering.hpp"

namespace perinom::detail {
namespace {

static_assert(sizeof(SuiteSparse_long) == sizeof(sunindextype), "UMFPACK's dl interface needs SUNDIALS' 64-bit indices");

struct Content {
  void* symbolic = nullptr;
  void* numeric = nullptr;
  double control[UMFPACK_CONTROL];
  double info[UMFPACK_INFO];
  std::vector<sunindextype> row_ptr, col;  // the pattern the symbolic analysis is of
  std::vector<double> rhs;                 // b when it is x's own storage
  FactorState state;
  int last_flag = SUNLS_SUCCESS;
};

Content* content(SUNLinearSolver s) { return static_cast<Content*>(s->content); }

void free_factors(Content* c) {
  if (c->numeric) umfpack_dl_free_numeric(&c->numeric);
  if (c->symbolic) umfpack_dl_free_symbolic(&c->symbolic);
}

bool same_pattern(const Content* c, sunindextype n, const sunindextype* row_ptr, const sunindextype* col) {
  return c->symbolic && c->row_ptr.size() == static_cast<std::size_t>(n + 1) &&
         std::equal(row_ptr, row_ptr + n + 1, c->row_ptr.begin()) &&
         std::equal(col, col + row_ptr[n], c->col.begin());
}

// A's CSR arrays read as CSC are A^T's: UMFPACK factors A^T, and solve asks for (A^T)^T x = b.
int setup(SUNLinearSolver s, SUNMatrix A) {
  Content* c = content(s);
  c->state = FactorState{};
  if (SUNMatGetID(A) != SUNMATRIX_SPARSE || SM_SPARSETYPE_S(A) != CSR_MAT || SM_ROWS_S(A) != SM_COLUMNS_S(A))
    return c->last_flag = SUNLS_ILL_INPUT;
  const sunindextype n = SM_ROWS_S(A);
  const sunindextype* row_ptr = SM_INDEXPTRS_S(A);
  const sunindextype* col = SM_INDEXVALS_S(A);
  const double* val = SM_DATA_S(A);
  if (c->numeric) umfpack_dl_free_numeric(&c->numeric);
  if (!same_pattern(c, n, row_ptr, col)) {
    free_factors(c);
    // The ordering the memory check counted (multipliers last: fill_ordering.hpp), with
    // UMFPACK's symmetric strategy, which keeps it and pivots on the diagonal where it can.
    // (The Jacobian's pattern is symmetric; left to itself UMFPACK also chose that strategy
    // and AMD, with the multipliers among the displacements.)
    const FillOrdering ordering = order_multipliers_last(n, row_ptr, col);
    const int status = ordering.ok ? umfpack_dl_qsymbolic(n, n, row_ptr, col, val, ordering.order.data(), &c->symbolic,
                                                          c->control, c->info)
                                   : UMFPACK_ERROR_out_of_memory;
    if (status != UMFPACK_OK) {
      c->state.out_of_memory = status == UMFPACK_ERROR_out_of_memory;
      c->symbolic = nullptr;
      return c->last_flag = c->state.out_of_memory ? SUNLS_MEM_FAIL : SUNLS_PACKAGE_FAIL_UNREC;
    }
    c->row_ptr.assign(row_ptr, row_ptr + n + 1);
    c->col.assign(col, col + row_ptr[n]);
  }
  const int status = umfpack_dl_numeric(row_ptr, col, val, c->symbolic, &c->numeric, c->control, c->info);
  c->state.rcond = status == UMFPACK_OK ? c->info[UMFPACK_RCOND] : 0.0;
  c->state.lu_entries = status == UMFPACK_OK ? c->info[UMFPACK_LNZ] + c->info[UMFPACK_UNZ] - double(n) : 0.0;
  if (status == UMFPACK_WARNING_singular_matrix) {
    c->state.singular = true;
    umfpack_dl_free_numeric(&c->numeric);  // no solve with a zero pivot
    return c->last_flag = SUNLS_LUFACT_FAIL;  // positive: KINSOL stops with KIN_LSETUP_FAIL
  }
  if (status != UMFPACK_OK) {
    c->state.out_of_memory = status == UMFPACK_ERROR_out_of_memory;
    if (c->numeric) umfpack_dl_free_numeric(&c->numeric);
    return c->last_flag = c->state.out_of_memory ? SUNLS_MEM_FAIL : SUNLS_PACKAGE_FAIL_UNREC;
  }
  return c->last_flag = SUNLS_SUCCESS;
}

int solve(SUNLinearSolver s, SUNMatrix A, N_Vector x, N_Vector b, realtype) {
  Content* c = content(s);
  if (!c->numeric) return c->last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  double* xd = N_VGetArrayPointer(x);
  const double* bd = N_VGetArrayPointer(b);
  if (xd == bd) {  // UMFPACK needs distinct right-hand side and solution
    c->rhs.assign(bd, bd + N_VGetLength(b));
    bd = c->rhs.data();
  }
  const int status = umfpack_dl_solve(UMFPACK_At, SM_INDEXPTRS_S(A), SM_INDEXVALS_S(A), SM_DATA_S(A), xd, bd,
                                      c->numeric, c->control, c->info);
  return c->last_flag = status == UMFPACK_OK ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_UNREC;
}

int free_solver(SUNLinearSolver s) {
  if (!s) return SUNLS_SUCCESS;
  if (Content* c = content(s)) {
    free_factors(c);
    delete c;
    s->content = nullptr;
  }
  SUNLinSolFreeEmpty(s);
  return SUNLS_SUCCESS;
}

}  // namespace

SUNLinearSolver umfpack_linear_solver(SUNContext context) {
  SUNLinearSolver s = SUNLinSolNewEmpty(context);
  if (!s) return nullptr;
  s->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  s->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  s->ops->initialize = [](SUNLinearSolver) { return SUNLS_SUCCESS; };
  s->ops->setup = setup;
  s->ops->solve = solve;
  s->ops->lastflag = [](SUNLinearSolver l) { return static_cast<sunindextype>(content(l)->last_flag); };
  s->ops->free = free_solver;
  auto* c = new Content;
  umfpack_dl_defaults(c->control);
  c->control[UMFPACK_STRATEGY] = UMFPACK_STRATEGY_SYMMETRIC;  // with qsymbolic: keep the given ordering
  s->content = c;
  return s;
}

FactorState umfpack_factor_state(SUNLinearSolver solver) { return content(solver)->state; }

double umfpack_condition_number(SUNLinearSolver solver, SUNMatrix A) {
  Content* c = content(solver);
  if (!c->numeric) return std::numeric_limits<double>::infinity();
  const sunindextype n = SM_ROWS_S(A);
  const sunindextype* row_ptr = SM_INDEXPTRS_S(A);
  const sunindextype* col = SM_INDEXVALS_S(A);
  const double* val = SM_DATA_S(A);
  std::vector<double> b;
  const auto with = [&](int system) {
    return [&, system](std::vector<double>& x) {
      b = x;
      umfpack_dl_solve(system, row_ptr, col, val, x.data(), b.data(), c->numeric, c->control, c->info);
    };
  };
  // The factors are A^T's (setup): UMFPACK_At solves A x = b, UMFPACK_A solves A^T x = b.
  return csr_norm1(n, row_ptr, col, val) * inverse_norm1_estimate(static_cast<std::size_t>(n), with(UMFPACK_At), with(UMFPACK_A));
}

}  // namespace perinom::detail

// Newton's check of its factors' size before it factors (factor_memory.hpp): the fill is
// the ordering's (CAMD, multipliers last), counted exactly on patterns whose fill is known
// (none for a band or an arrow whose hub is eliminated last, all of it for a dense matrix),
// UMFPACK makes what was counted on a saddle point, and a factorization that would not
// fit is refused with an error naming the key to change (solver.linear_solver, solver.type
// for direct), never left to the OOM killer.
#include <catch2/catch.hpp>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <vector>

#include "../../lib/solvers/factor_memory.hpp"
#include "../../lib/solvers/umfpack_linear_solver.hpp"
#include "perinom/core/error.hpp"
#include "perinom/core/memory.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/registry.hpp"
#include "perinom/solvers/direct.hpp"
#include "perinom/solvers/jacobian.hpp"
#include "perinom/solvers/newton.hpp"

using namespace perinom;

namespace {

/// The pattern of an n x n matrix with the entries (i, j) keep(i, j) says (values 1).
template <class Keep>
CsrMatrix pattern(int n, Keep keep) {
  CsrMatrix A;
  A.rows = n;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      if (keep(i, j)) A.col.push_back(j), A.val.push_back(1.0);
    A.row_ptr.push_back(static_cast<std::int64_t>(A.col.size()));
  }
  return A;
}

}  // namespace

TEST_CASE("the predicted fill of L + U is the ordering's: none for a band or an arrow, all for a dense matrix",
          "[solvers][newton]") {
  const int n = 60;
  const CsrMatrix band = pattern(n, [](int i, int j) { return std::abs(i - j) <= 1; });
  CHECK(detail::predict_lu_factors(band).entries == Approx(3.0 * n - 2.0).epsilon(1e-12));
  // The hub first: eliminated in that order it fills the whole matrix (n^2 entries); CAMD
  // takes it last and nothing fills.
  const CsrMatrix arrow = pattern(n, [](int i, int j) { return i == j || i == 0 || j == 0; });
  CHECK(detail::predict_lu_factors(arrow).entries == Approx(3.0 * n - 2.0).epsilon(1e-12));
  const CsrMatrix dense = pattern(n, [](int, int) { return true; });
  const detail::FactorPrediction full = detail::predict_lu_factors(dense);
  CHECK(full.entries == Approx(double(n) * n).epsilon(1e-12));
  // The bytes grow with the Jacobian's entries and the factors' (the rates of factor_memory.cpp).
  CHECK(full.bytes > detail::predict_lu_factors(band).bytes);
  CHECK(detail::predict_lu_factors(CsrMatrix{}).entries == 0.0);
}

TEST_CASE("UMFPACK factors a saddle point with the fill the check predicted: its multipliers pivot last",
          "[solvers][newton]") {
  // The plate's support at the face makes Newton's Jacobian [K, kappa E^T; kappa E, 0]. With
  // AMD's ordering UMFPACK met the multipliers' zero diagonals among the displacements and
  // pivoted off the diagonal: here it made 4.84e6 entries, 3.7% more than the ordering with
  // the multipliers last counts and makes (the plate with a hole at dx = 1 mm: 36% more, the
  // memory check's prediction 23% below the peak).
  Problem p = build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/uniaxial_compression.yaml"));
  StaticSystem system(p.physics(), p.loading);
  REQUIRE(system.multipliers() > 0);
  std::vector<double> z(system.dofs(), 0.0);
  system.assemble(z.data());
  const CsrMatrix& J = system.jacobian();
  const double predicted = detail::predict_lu_factors(J).entries;

  SUNContext ctx = nullptr;
  REQUIRE(SUNContext_Create(nullptr, &ctx) == 0);
  SUNMatrix A = SUNSparseMatrix(J.rows, J.rows, static_cast<sunindextype>(J.col.size()), CSR_MAT, ctx);
  std::copy(J.row_ptr.begin(), J.row_ptr.end(), SM_INDEXPTRS_S(A));
  std::copy(J.col.begin(), J.col.end(), SM_INDEXVALS_S(A));
  std::copy(J.val.begin(), J.val.end(), SM_DATA_S(A));
  SUNLinearSolver ls = detail::umfpack_linear_solver(ctx);
  REQUIRE(SUNLinSolSetup(ls, A) == SUNLS_SUCCESS);
  const double made = detail::umfpack_factor_state(ls).lu_entries;
  INFO("predicted " << predicted << ", UMFPACK made " << made);
  CHECK(made == Approx(predicted).epsilon(0.005));
  SUNMatDestroy(A);
  SUNLinSolFree(ls);
  SUNContext_Free(&ctx);
}

TEST_CASE("factors that would not fit are refused with the key and the cures", "[solvers][newton]") {
  const double mib = 1048576.0;
  // A limit (--max-memory) counts what the process holds too.
  const double held = resident_bytes();
  REQUIRE(held > 0.0);
  const std::string key = "solver.linear_solver: KLU's LU factors", cures = "use solver.type adr";
  CHECK_NOTHROW(detail::require_factor_memory(1.0 * mib, key, cures, held + 2.0 * mib));
  CHECK_THROWS_AS(detail::require_factor_memory(1.0 * mib, key, cures, held + 0.5 * mib), InputError);
  CHECK_THROWS_WITH(detail::require_factor_memory(10.0 * mib, key, cures, held + 0.5 * mib),
                    Catch::StartsWith(key + " would need about 10 MiB beside the ") &&
                        Catch::Contains("MiB the process holds, more than the ") &&
                        Catch::Contains("allowed by --max-memory; use solver.type adr") &&
                        !Catch::Contains("overrides"));
  // Without a limit the factors alone meet the memory available now.
  const double available = available_memory();
  REQUIRE(available > 0.0);
  CHECK_NOTHROW(detail::require_factor_memory(0.5 * available, key, cures, 0.0));
  CHECK_THROWS_WITH(detail::require_factor_memory(2.0 * available, key, cures, 0.0),
                    Catch::Contains("MiB of memory available (the process holds ") &&
                        Catch::Contains("MiB); use solver.type adr (--max-memory overrides the limit)"));
  // The direct solver's rates grow with K_T's entries and L's.
  CHECK(detail::predict_cholesky_bytes(2e6, 3e7) > detail::predict_cholesky_bytes(2e6, 1e7));
  CHECK(detail::predict_cholesky_bytes(2e6, 1e7) > detail::predict_cholesky_bytes(1e6, 1e7));
}

TEST_CASE("Newton refuses, before factoring, a Jacobian whose factors exceed its memory limit", "[solvers][newton]") {
  Problem p = build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/uniaxial_compression.yaml"));
  for (const char* solver : {"klu", "umfpack"}) {
    INFO(solver);
    std::vector<double> u;
    NewtonOptions opt;
    opt.linear_solver = solver;
    opt.memory_limit = resident_bytes() + 1e6;  // the 2,592-particle plate's solve adds about 100 MiB
    CHECK_THROWS_WITH(solve_newton(p.physics(), p.loading, opt, u),
                      Catch::StartsWith("solver.linear_solver: ") && Catch::Contains("allowed by --max-memory"));
    opt.memory_limit = resident_bytes() + 4e9;
    CHECK(solve_newton(p.physics(), p.loading, opt, u).converged);
  }
}

TEST_CASE("direct refuses, after CHOLMOD's analysis, a factor that exceeds its memory limit", "[solvers][direct]") {
  Problem p = build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/uniaxial_compression.yaml"));
  std::vector<double> u;
  DirectOptions opt;
  opt.memory_limit = resident_bytes() + 1e6;  // the 2,592-particle plate's factor adds about 35 MiB
  CHECK_THROWS_WITH(solve_direct(p.physics(), p.loading, u, opt),
                    Catch::StartsWith("solver.type: direct: CHOLMOD's Cholesky factor of K_T (") &&
                        Catch::Contains("allowed by --max-memory; use solver.type adr"));
  opt.memory_limit = resident_bytes() + 4e9;
  CHECK(solve_direct(p.physics(), p.loading, u, opt).converged);
}

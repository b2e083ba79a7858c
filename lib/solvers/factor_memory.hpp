#pragma once
/// @file The memory a direct solver's LU factors of a Jacobian will take, predicted from the
/// pattern before anything is factored, and the refusal of a factorization that would not
/// fit. A nonlocal Jacobian fills in far beyond its own entries (the 2-D plate at 41k
/// particles: 1.7e7 entries, 2.3e8 in L + U), so the estimate made before the build, which
/// knows no ordering, cannot say it; without this check a Newton run too large for the
/// machine was killed by the kernel's OOM killer with no message and no output.
#include "perinom/solvers/jacobian.hpp"

namespace perinom::detail {

struct FactorPrediction {
  double entries = 0.0;  ///< in L + U: twice AMD's count of L below the diagonal, plus n
  double largest_column = 0.0;  ///< of L, with its diagonal (AMD_DMAX): the largest front's size
  double bytes = 0.0;    ///< the peak resident size the solve adds, Jacobian and factors (measured rates)
};

/// AMD's fill of A + A^T's pattern: UMFPACK's symmetric strategy and KLU (the AMD ordering
/// newton.cpp asks for) order by the same AMD, so L + U holds about this many entries when
/// the pivots stay on the diagonal (on the 2-D plate UMFPACK made 10-12% more, with its
/// off-diagonal pivots; on the 3-D cantilever 30% fewer, AMD's count being an upper bound).
FactorPrediction predict_lu_factors(const CsrMatrix& A);

/// Throws InputError (exit 2, naming solver.linear_solver) when the factors would not fit:
/// the process's resident size plus the prediction above `limit` bytes, or, with limit 0,
/// the prediction above the memory available now (nothing is refused when that is unknown).
void require_factor_memory(const FactorPrediction& factors, const CsrMatrix& A, const char* factorizer,
                           double limit);

}  // namespace perinom::detail

#pragma once
/// @file The memory a direct solver's factors will take, predicted from the pattern before
/// anything is factored, and the refusal of a factorization that would not fit. A nonlocal
/// stiffness fills in far beyond its own entries (the 2-D plate at 41k particles: 1.7e7
/// Jacobian entries, 2.3e8 in UMFPACK's L + U), so the estimate made before the build, which
/// knows no ordering, cannot say it; without this check a Newton or direct run too large for
/// the machine was killed by the kernel's OOM killer with no message and no output.
#include <string>

#include "perinom/solvers/jacobian.hpp"

namespace perinom::detail {

struct FactorPrediction {
  double entries = 0.0;  ///< in L + U: twice AMD's count of L below the diagonal, plus n
  double largest_column = 0.0;  ///< of L, with its diagonal (AMD_DMAX): the largest front's size
  double bytes = 0.0;    ///< the peak resident size the solve adds, Jacobian and factors (measured rates)
};

/// Newton's LU factors: AMD's fill of A + A^T's pattern. UMFPACK's symmetric strategy and KLU
/// (the AMD ordering newton.cpp asks for) order by the same AMD, so L + U holds about this many
/// entries when the pivots stay on the diagonal (on the 2-D plate UMFPACK made 10-12% more,
/// with its off-diagonal pivots; on the 3-D cantilever 30% fewer, AMD's count being an upper
/// bound).
FactorPrediction predict_lu_factors(const CsrMatrix& A);

/// The peak resident size `direct` adds as CHOLMOD factors K_T of `matrix_entries` into a
/// supernodal L of `factor_values` (its xsize after the analysis), in bytes.
double predict_cholesky_bytes(double matrix_entries, double factor_values);

/// Throws InputError (exit 2) "<subject> would need about B MiB ...; <cures>" when the
/// process's resident size plus `bytes` exceeds `limit` (--max-memory), or, with limit 0, when
/// `bytes` exceeds the memory available now (nothing is refused when that is unknown).
/// `subject` starts with the key to change.
void require_factor_memory(double bytes, const std::string& subject, const std::string& cures, double limit);

}  // namespace perinom::detail

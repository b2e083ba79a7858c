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
  double entries = 0.0;  ///< in L + U: twice the ordering's count of L below the diagonal, plus n
  double largest_column = 0.0;  ///< of L, with its diagonal (CAMD_DMAX): the largest front's size
  double bytes = 0.0;    ///< the peak resident size the solve adds, Jacobian and factors (measured rates)
};

/// Newton's LU factors: the fill of order_multipliers_last (fill_ordering.hpp), the ordering
/// UMFPACK factors in, so L + U holds this many entries while its pivots stay on the diagonal
/// (the uniaxial plate and the plate with a hole: within 0.1%). KLU orders by its own BTF and
/// AMD; the same count serves it (its peak on the plate with a hole 9.5% above the prediction).
/// The count is an upper bound where rows are long (small 3-D Jacobians: +23% on the peak).
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

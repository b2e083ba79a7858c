#include "factor_memory.hpp"

#include <amd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "perinom/core/error.hpp"
#include "perinom/core/memory.hpp"

namespace perinom::detail {
namespace {

// The peak resident size a Newton solve adds to what the process holds as it starts: per
// entry of the Jacobian (KINSOL's copy, the assembly's work), per predicted entry of L + U
// (values, indices) and per square of the largest column of L, AMD's bound on the largest
// frontal matrix (UMFPACK's dense work space: about 2.6 fronts of doubles). Fitted with
// UMFPACK (VmHWM at the end less VmRSS at the check) on the 2-D plate
// (examples/uniaxial_compression.yaml, Newton) at 10k and 41k particles and the 3-D
// cantilever (verification/formulation) at 8 particles through, within 1% on those; the
// checks outside the fit are in docs/scene-format.md.
constexpr double bytes_per_jacobian_entry = 40.0;
constexpr double bytes_per_factor_entry = 12.0;
constexpr double bytes_per_front_entry = 21.0;
// The same for `direct`, per entry of K_T and per value of CHOLMOD's supernodal L (its size
// after the analysis, the supernodes' zeros included): 8 bytes for the values, and K_T's
// permuted copy. Fitted on six runs (the 2-D plate at 2.6k, 10k, 41k particles, the 3-D
// cantilever at 4, 6, 8 through: -15% to +14% of the added peak); the 3-D cantilever at 16
// through, outside the fit, +0.4% (17,886 MiB predicted, 17,807 measured).
constexpr double bytes_per_reduced_entry = 8.3;
constexpr double bytes_per_cholesky_value = 8.2;

double mib(double bytes) { return bytes / 1048576.0; }

}  // namespace

FactorPrediction predict_lu_factors(const CsrMatrix& A) {
  static_assert(sizeof(SuiteSparse_long) == sizeof(std::int64_t), "AMD's l interface takes 64-bit indices");
  const auto n = static_cast<SuiteSparse_long>(A.rows);
  FactorPrediction p;
  if (n == 0) return p;
  std::vector<SuiteSparse_long> perm(static_cast<std::size_t>(n));
  double control[AMD_CONTROL], info[AMD_INFO];
  amd_l_defaults(control);
  // AMD's defaults, as UMFPACK and KLU call it: rows longer than 10 sqrt(n) (a small 3-D
  // Jacobian's) are ordered last, and the count is then a rough upper bound (without that
  // rule the 3-D cantilever at 4 through counted 1.05e6 entries where UMFPACK made 2.54e6).
  // The pattern only: AMD orders the symmetric pattern A + A^T (A's rows read as columns).
  const SuiteSparse_long status = amd_l_order(n, reinterpret_cast<const SuiteSparse_long*>(A.row_ptr.data()),
                                              reinterpret_cast<const SuiteSparse_long*>(A.col.data()), perm.data(),
                                              control, info);
  if (status != AMD_OK && status != AMD_OK_BUT_JUMBLED) return p;  // (out of memory: the factors would not fit either)
  p.entries = 2.0 * info[AMD_LNZ] + double(n);
  p.largest_column = info[AMD_DMAX];
  p.bytes = bytes_per_jacobian_entry * double(A.col.size()) + bytes_per_factor_entry * p.entries +
            bytes_per_front_entry * p.largest_column * p.largest_column;
  return p;
}

double predict_cholesky_bytes(double matrix_entries, double factor_values) {
  return bytes_per_reduced_entry * matrix_entries + bytes_per_cholesky_value * factor_values;
}

void require_factor_memory(double bytes, const std::string& subject, const std::string& cures, double limit) {
  const double held = resident_bytes();
  const double room = limit > 0.0 ? limit - held : available_memory();
  if (bytes <= 0.0 || (room <= 0.0 && limit <= 0.0) || bytes <= room) return;
  char sizes[300];
  if (limit > 0.0)
    std::snprintf(sizes, sizeof sizes,
                  " would need about %.0f MiB beside the %.0f MiB the process holds, more than the %.0f MiB allowed by "
                  "--max-memory; ",
                  mib(bytes), mib(held), mib(limit));
  else
    std::snprintf(sizes, sizeof sizes,
                  " would need about %.0f MiB, more than the %.0f MiB of memory available (the process holds %.0f "
                  "MiB); ",
                  mib(bytes), mib(room), mib(held));
  throw InputError(subject + sizes + cures + (limit > 0.0 ? "" : " (--max-memory overrides the limit)"));
}

}  // namespace perinom::detail

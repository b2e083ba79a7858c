#include "factor_memory.hpp"

#include <cstdio>
#include <string>
#include <vector>

#include "perinom/core/error.hpp"
#include "perinom/core/memory.hpp"
#include "fill_ordering.hpp"

namespace perinom::detail {
namespace {

// The peak resident size a Newton solve adds to what the process holds as it starts: per
// entry of the Jacobian (KINSOL's copy, the assembly's work, UMFPACK's), per predicted entry
// of L + U (values, indices) and per square of the largest column of L, the ordering's bound
// on the largest frontal matrix (UMFPACK's dense work space). Fitted with UMFPACK (VmHWM at
// the end against VmRSS at the check, the largest error made smallest) on six runs above
// 500 MiB: the 2-D plate (examples/uniaxial_compression.yaml, Newton) at 10k, 41k and 101k
// particles, the 3-D cantilever (verification/formulation) at 6 and 8 particles through, the
// plate with a hole (a plastic load path) at dx = 1 mm; the figures are in docs/scene-format.md.
constexpr double bytes_per_jacobian_entry = 72.0;
constexpr double bytes_per_factor_entry = 8.0;
constexpr double bytes_per_front_entry = 15.0;
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
  FactorPrediction p;
  const FillOrdering f = order_multipliers_last(A.rows, A.row_ptr.data(), A.col.data());
  if (!f.ok || A.rows == 0) return p;
  p.entries = 2.0 * f.lower_entries + double(A.rows);
  p.largest_column = f.largest_column;
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

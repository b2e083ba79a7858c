#pragma once
/// @file The fill-reducing ordering of Newton's Jacobian, shared by the factorization and the
/// prediction of its memory. The Jacobian of a scene with face-located constraints is a
/// saddle point [K, kappa E^T; kappa E, 0]: the multipliers' rows have no diagonal entry. AMD
/// orders them among the displacements, where the factorization cannot pivot on their zero
/// diagonal: UMFPACK then pivoted off the diagonal (221 times on the plate with a hole at
/// dx = 1 mm, 216 multipliers) and made 4.53e7 entries in L + U where AMD had counted 3.17e7
/// (the prediction 23% below the peak). Ordered last, after every displacement, each
/// multiplier meets the Schur complement -kappa^2 E K^-1 E^T, whose diagonal is not zero:
/// the pivots stay on the diagonal and L + U holds what the ordering counted (3.33e7 there,
/// the peak 938 -> 714 MiB).
#include <cstdint>
#include <vector>

namespace perinom::detail {

struct FillOrdering {
  std::vector<std::int64_t> order;  ///< order[k] = the k-th pivot's row (and column)
  double lower_entries = 0.0;       ///< in L below the diagonal, with diagonal pivots
  double largest_column = 0.0;      ///< of L, with its diagonal: the largest front's size
  bool ok = false;                  ///< false: out of memory (the factors would not fit either)
};

/// CAMD on the pattern of A + A^T (n x n, compressed rows or columns: the pattern only),
/// with the rows that have no diagonal entry constrained to come after all the others;
/// CAMD's defaults otherwise, as AMD's in UMFPACK and KLU: rows longer than 10 sqrt(n) (a
/// small 3-D Jacobian's) are ordered last within their set, and the count is then an upper
/// bound. On a pattern with a full diagonal it is AMD's ordering.
FillOrdering order_multipliers_last(std::int64_t n, const std::int64_t* row_ptr, const std::int64_t* col);

}  // namespace perinom::detail

#include "fill_ordering.hpp"

#include <camd.h>

namespace perinom::detail {

FillOrdering order_multipliers_last(std::int64_t n, const std::int64_t* row_ptr, const std::int64_t* col) {
  static_assert(sizeof(SuiteSparse_long) == sizeof(std::int64_t), "CAMD's l interface takes 64-bit indices");
  FillOrdering f;
  if (n <= 0) {
    f.ok = true;
    return f;
  }
  const auto size = static_cast<std::size_t>(n);
  std::vector<SuiteSparse_long> set(size, 1);  // 0: ordered first; 1: after every 0
  for (std::int64_t i = 0; i < n; ++i)
    for (std::int64_t k = row_ptr[i]; k < row_ptr[i + 1]; ++k)
      if (col[k] == i) set[static_cast<std::size_t>(i)] = 0;
  f.order.resize(size);
  double control[CAMD_CONTROL], info[CAMD_INFO];
  camd_l_defaults(control);
  const SuiteSparse_long status =
      camd_l_order(n, reinterpret_cast<const SuiteSparse_long*>(row_ptr), reinterpret_cast<const SuiteSparse_long*>(col),
                   reinterpret_cast<SuiteSparse_long*>(f.order.data()), control, info, set.data());
  f.ok = status == CAMD_OK || status == CAMD_OK_BUT_JUMBLED;
  f.lower_entries = info[CAMD_LNZ];
  f.largest_column = info[CAMD_DMAX];
  return f;
}

}  // namespace perinom::detail

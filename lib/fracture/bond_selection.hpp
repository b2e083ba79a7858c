#pragma once
// Bond selection in one parallel pass over the live bonds, for the fracture criteria (internal
// to lib/fracture): no per-bond array, the same result for any thread count.
#include <omp.h>

#include <algorithm>
#include <vector>

#include "perinom/fracture/criteria.hpp"

namespace perinom::detail {

/// The largest value(i, j) over the live bonds (0 with none); rows in parallel, the same
/// result for any thread count (a maximum does not depend on the order).
template <class Value>
double live_maximum(const BondGraph& g, const Value& value) {
  double top = 0.0;
  const std::size_t n = g.rows();
#pragma omp parallel for schedule(static) reduction(max : top)
  for (std::size_t i = 0; i < n; ++i)
    for (Offset k = g.begin(i); k < g.end(i); ++k)
      if (g.alive(k)) top = std::max(top, value(i, static_cast<std::size_t>(g.col(k))));
  return top;
}

/// The live bonds (i, j) for which due(i, j) holds, in row order whatever the thread count
/// (each thread takes a contiguous block of rows; the blocks are joined in order). One pass,
/// no per-bond array: what a criterion costs per step.
template <class Due>
std::vector<BondPair> live_bonds_where(const BondGraph& g, const Due& due) {
  std::vector<std::vector<BondPair>> found;
#pragma omp parallel
  {
#pragma omp single
    found.resize(static_cast<std::size_t>(omp_get_num_threads()));
    std::vector<BondPair>& mine = found[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < g.rows(); ++i) {
      // First whether any bond of the row is due, in a loop without branches or stores that
      // the compiler can vectorize; then, rarely, the row again to keep them.
      int any = 0;
      for (Offset k = g.begin(i); k < g.end(i); ++k) any |= int(g.alive(k)) & int(due(i, static_cast<std::size_t>(g.col(k))));
      if (!any) continue;
      for (Offset k = g.begin(i); k < g.end(i); ++k)
        if (g.alive(k) && due(i, static_cast<std::size_t>(g.col(k)))) mine.emplace_back(static_cast<ParticleId>(i), g.col(k));
    }
  }
  std::vector<BondPair> out;
  for (auto& f : found) out.insert(out.end(), f.begin(), f.end());
  return out;
}

}  // namespace perinom::detail

#pragma once
// Bond selection in one parallel pass over the live bonds, for the fracture criteria (internal
// to lib/fracture): no per-bond array, the same result for any thread count.
#include <omp.h>

#include <algorithm>
#include <vector>

#include "perinom/fracture/criteria.hpp"

namespace perinom::detail {

/// The largest value(i, j) over each row's live bonds (0 for a row without): N values.
template <class Value>
std::vector<double> live_row_maxima(const BondGraph& g, const Value& value) {
  std::vector<double> top(g.rows(), 0.0);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < g.rows(); ++i) {
    double t = 0.0;
    for (Offset k = g.begin(i); k < g.end(i); ++k)
      t = std::max(t, g.alive(k) ? value(i, static_cast<std::size_t>(g.col(k))) : 0.0);
    top[i] = t;
  }
  return top;
}

/// The largest value(i, j) over the live bonds of rows row(0) .. row(count - 1) (0 with none);
/// rows in parallel, the same result for any thread count (a maximum does not depend on the
/// order).
template <class Row, class Value>
double live_maximum(const BondGraph& g, std::size_t count, const Row& row, const Value& value) {
  double top = 0.0;
#pragma omp parallel for schedule(static) reduction(max : top)
  for (std::size_t r = 0; r < count; ++r) {
    const std::size_t i = row(r);
    for (Offset k = g.begin(i); k < g.end(i); ++k)
      if (g.alive(k)) top = std::max(top, value(i, static_cast<std::size_t>(g.col(k))));
  }
  return top;
}

/// The same over every row, and over the given rows.
template <class Value>
double live_maximum(const BondGraph& g, const Value& value) {
  return live_maximum(g, g.rows(), [](std::size_t r) { return r; }, value);
}
template <class Value>
double live_maximum(const BondGraph& g, const std::vector<ParticleId>& rows, const Value& value) {
  return live_maximum(g, rows.size(), [&rows](std::size_t r) { return static_cast<std::size_t>(rows[r]); }, value);
}

/// The live bonds (i, j) of rows row(0) .. row(count - 1) (ascending) for which due(i, j)
/// holds, in row order whatever the thread count (each thread takes a contiguous block of
/// rows; the blocks are joined in order). One pass, no per-bond array: what a criterion costs
/// per step.
template <class Row, class Due>
std::vector<BondPair> live_bonds_where(const BondGraph& g, std::size_t count, const Row& row, const Due& due) {
  std::vector<std::vector<BondPair>> found;
#pragma omp parallel
  {
#pragma omp single
    found.resize(static_cast<std::size_t>(omp_get_num_threads()));
    std::vector<BondPair>& mine = found[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
    for (std::size_t r = 0; r < count; ++r) {
      const std::size_t i = row(r);
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

/// The same over every row, and over the given rows (ascending).
template <class Due>
std::vector<BondPair> live_bonds_where(const BondGraph& g, const Due& due) {
  return live_bonds_where(g, g.rows(), [](std::size_t r) { return r; }, due);
}
template <class Due>
std::vector<BondPair> live_bonds_where(const BondGraph& g, const std::vector<ParticleId>& rows, const Due& due) {
  return live_bonds_where(g, rows.size(), [&rows](std::size_t r) { return static_cast<std::size_t>(rows[r]); }, due);
}

}  // namespace perinom::detail

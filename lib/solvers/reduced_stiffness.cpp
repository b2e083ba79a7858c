// K_T = T^T K T straight from the model's tangent rows, in parallel (galerkin.hpp).
#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

#include "galerkin.hpp"
#include "perinom/core/error.hpp"
#include "perinom/core/parallel.hpp"

namespace perinom::detail {
namespace {

using Entry = std::pair<int, double>;
using Row = std::vector<Entry>;

/// A dense row of n_free values with the list of columns touched, one per thread: rows that
/// meet T's constrained rows (a face-located support's reconstruction, which can reach far
/// along the face) add many entries per column, and are summed here rather than sorted.
struct Accumulator {
  std::vector<double> value;
  std::vector<char> touched;
  std::vector<int> columns;
  explicit Accumulator(int n) : value(static_cast<std::size_t>(n), 0.0), touched(static_cast<std::size_t>(n), 0) {}
  void add(int c, double v) {
    if (!touched[c]) touched[c] = 1, columns.push_back(c);
    value[c] += v;
  }
  /// Writes the sum into row (sorted) and clears.
  void take(Row& row) {
    std::sort(columns.begin(), columns.end());
    row.clear();
    row.reserve(columns.size());
    for (const int c : columns) row.emplace_back(c, value[c]), value[c] = 0.0, touched[c] = 0;
    columns.clear();
  }
};

/// Rows of (column, value) pairs, each sorted, as CSR with `columns` columns (the rows
/// released as they are copied). Throws InputError past 2^31 - 1 nonzeros.
RowSparse to_csr(std::vector<Row>& rows, int columns) {
  std::int64_t entries = 0;
  for (const Row& row : rows) entries += static_cast<std::int64_t>(row.size());
  if (entries > std::numeric_limits<int>::max())
    throw InputError("the reduced stiffness has " + std::to_string(entries) +
                     " nonzeros, more than 32-bit indices hold (2^31 - 1): use solver.type adr");
  RowSparse K(static_cast<int>(rows.size()), columns);
  std::vector<int> start(rows.size() + 1, 0);
  for (std::size_t r = 0; r < rows.size(); ++r) start[r + 1] = start[r] + static_cast<int>(rows[r].size());
  K.resizeNonZeros(start.back());
  std::copy(start.begin(), start.end(), K.outerIndexPtr());
  parallel_for(rows.size(), [&](std::size_t r) {
    for (std::size_t k = 0; k < rows[r].size(); ++k) {
      K.innerIndexPtr()[start[r] + k] = rows[r][k].first;
      K.valuePtr()[start[r] + k] = rows[r][k].second;
    }
    Row().swap(rows[r]);
  });
  return K;
}

}  // namespace

TRows::TRows(const Sparse& T, const std::vector<std::int64_t>& free_index) : index(free_index), fixed(T.rows()) {
  for (Eigen::Index col = 0; col < T.cols(); ++col)
    for (Sparse::InnerIterator it(T, col); it; ++it)
      if (index[it.row()] < 0) fixed[it.row()].emplace_back(static_cast<int>(col), it.value());
  columns = static_cast<int>(T.cols());
}

RowSparse reduced_stiffness(const TangentModel& model, const TRows& t) {
  const int d = model.dofs_per_particle();
  std::vector<Accumulator> scratch(static_cast<std::size_t>(omp_get_max_threads()), Accumulator(t.columns));
  // 1. K T by rows: the free rows (K_T's own, before T^T adds to some) and the constrained
  //    rows T reads.
  std::vector<Row> rows(static_cast<std::size_t>(t.columns));
  std::vector<Row> fixed_rows(t.index.size());
  model.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
    Accumulator& acc = scratch[static_cast<std::size_t>(omp_get_thread_num())];
    bool reaches_constrained = false;
    for (const ParticleId c : cols)
      for (int b = 0; b < d; ++b) reaches_constrained = reaches_constrained || !t.fixed[c * d + b].empty();
    for (int a = 0; a < d; ++a) {
      const std::size_t g = i * d + a;
      if (t.index[g] < 0 && t.fixed[g].empty()) continue;  // a dof T sets to zero
      Row& row = t.index[g] >= 0 ? rows[static_cast<std::size_t>(t.index[g])] : fixed_rows[g];
      if (!reaches_constrained) {
        // Free columns only: they come in order (cols sorted, the free index monotone).
        row.clear();
        row.reserve(cols.size() * d);
        for (std::size_t q = 0; q < cols.size(); ++q)
          for (int b = 0; b < d; ++b) {
            const std::size_t h = static_cast<std::size_t>(cols[q]) * d + b;
            if (t.index[h] >= 0) row.emplace_back(static_cast<int>(t.index[h]), blocks[(q * d + a) * d + b]);
          }
        continue;
      }
      for (std::size_t q = 0; q < cols.size(); ++q)
        for (int b = 0; b < d; ++b) {
          const std::size_t h = static_cast<std::size_t>(cols[q]) * d + b;
          const double v = blocks[(q * d + a) * d + b];
          if (t.index[h] >= 0) acc.add(static_cast<int>(t.index[h]), v);
          for (const auto& [r, x] : t.fixed[h]) acc.add(r, x * v);
        }
      acc.take(row);
    }
  });
  // 2. T^T: free row r gains x (K T)_g for each constrained dof g whose T row holds (r, x).
  std::vector<std::vector<std::pair<std::int64_t, double>>> gains(rows.size());
  std::vector<std::size_t> gaining;
  for (std::size_t g = 0; g < t.index.size(); ++g)
    for (const auto& [r, x] : t.fixed[g]) {
      if (gains[static_cast<std::size_t>(r)].empty()) gaining.push_back(static_cast<std::size_t>(r));
      gains[static_cast<std::size_t>(r)].emplace_back(static_cast<std::int64_t>(g), x);
    }
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t k = 0; k < gaining.size(); ++k) {
    Accumulator& acc = scratch[static_cast<std::size_t>(omp_get_thread_num())];
    Row& row = rows[gaining[k]];
    for (const auto& [c, v] : row) acc.add(c, v);
    for (const auto& [g, x] : gains[gaining[k]])
      for (const auto& [c, v] : fixed_rows[static_cast<std::size_t>(g)]) acc.add(c, x * v);
    acc.take(row);
  }
  return to_csr(rows, t.columns);
}

RowSparse own_stiffness(const TangentModel& model, const std::vector<std::int64_t>& free_index,
                        const std::vector<int>& column, int columns) {
  const int d = model.dofs_per_particle();
  int own = 0;
  for (const auto k : free_index) own += k >= 0 ? 1 : 0;
  std::vector<Row> rows(static_cast<std::size_t>(own));
  model.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
    for (int a = 0; a < d; ++a) {
      const std::int64_t r = free_index[i * d + a];
      if (r < 0) continue;
      Row& row = rows[static_cast<std::size_t>(r)];
      row.clear();
      row.reserve(cols.size() * d);
      for (std::size_t q = 0; q < cols.size(); ++q)
        for (int b = 0; b < d; ++b) {
          const int c = column[static_cast<std::size_t>(cols[q]) * d + b];
          if (c >= 0) row.emplace_back(c, blocks[(q * d + a) * d + b]);
        }
      std::sort(row.begin(), row.end());  // the ghosts' global numbers come in no order
    }
  });
  return to_csr(rows, columns);
}

}  // namespace perinom::detail

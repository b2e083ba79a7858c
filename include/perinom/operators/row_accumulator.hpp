#pragma once
/// @file A sparse accumulator: gathers the entries of one matrix row in any order; and the
/// one loop that assembles rows with it (stored S, tangent rows of every model).
#include <algorithm>
#include <functional>
#include <vector>

#include "perinom/core/types.hpp"

namespace perinom {

/// Accumulates blocks of `block` doubles per column for one row at a time, in O(touched)
/// per row (dense scratch of N blocks, reused across rows; one per thread).
class RowAccumulator {
 public:
  RowAccumulator(std::size_t columns, int block)
      : block_(block), slot_(columns, -1), values_(), cols_() {}

  /// The block of column j, zero-initialised on first touch.
  double* at(ParticleId j) {
    int& s = slot_[j];
    if (s < 0) {
      s = static_cast<int>(cols_.size());
      cols_.push_back(j);
      values_.resize(values_.size() + block_, 0.0);
    }
    return values_.data() + static_cast<std::size_t>(s) * block_;
  }

  /// Sorts the touched columns; afterwards cols() and block(k) list the row in column order
  /// (sorted = false: in the order first touched, for a reader that needs no order).
  void finish(bool sorted = true) {
    order_.resize(cols_.size());
    for (std::size_t k = 0; k < cols_.size(); ++k) order_[k] = static_cast<int>(k);
    if (sorted) std::sort(order_.begin(), order_.end(), [&](int a, int b) { return cols_[a] < cols_[b]; });
    sorted_cols_.resize(cols_.size());
    for (std::size_t k = 0; k < cols_.size(); ++k) sorted_cols_[k] = cols_[order_[k]];
  }
  const std::vector<ParticleId>& cols() const { return sorted_cols_; }
  const double* block(std::size_t k) const {
    return values_.data() + static_cast<std::size_t>(order_[k]) * block_;
  }

  /// Forgets the row (touching only what was set).
  void clear() {
    for (const ParticleId j : cols_) slot_[j] = -1;
    cols_.clear();
    values_.clear();
  }

 private:
  int block_;
  std::vector<int> slot_;
  std::vector<double> values_;
  std::vector<ParticleId> cols_, sorted_cols_;
  std::vector<int> order_;
};

/// Adds the contributions of row i to acc (columns may repeat).
using RowFill = std::function<void(std::size_t, RowAccumulator&)>;
/// visit(i, cols, blocks): row i's columns, sorted, and one block per column (blocks[k *
/// block + c] for cols[k]).
using BlockRowVisitor =
    std::function<void(std::size_t, const std::vector<ParticleId>&, const std::vector<double>&)>;

/// Visits rows 0 .. rows - 1 of a sparse matrix of `columns` block columns, `block` values per
/// block (dofs^2 for dofs unknowns per particle), in parallel: each thread takes its fill
/// from make_fill() (called once per thread, concurrently; so a fill may keep scratch of its
/// own) and its own accumulator; visit is called concurrently for distinct rows.
void for_each_block_row(std::size_t rows, std::size_t columns, int block, const std::function<RowFill()>& make_fill,
                        const BlockRowVisitor& visit);
/// The same for the listed rows only; sorted = false hands visit the columns in no order.
void for_each_block_row(const std::vector<ParticleId>& rows, std::size_t columns, int block,
                        const std::function<RowFill()>& make_fill, const BlockRowVisitor& visit,
                        bool sorted = true);

}  // namespace perinom

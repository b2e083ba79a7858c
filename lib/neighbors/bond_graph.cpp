#include "perinom/neighbors/bond_graph.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace perinom {

BondGraph::BondGraph(Families families, std::size_t columns) : families_(std::move(families)) {
  const std::size_t n = families_.particles();
  std::size_t ncols = std::max(columns, n);
  for (const ParticleId j : families_.neighbors) ncols = std::max(ncols, static_cast<std::size_t>(j) + 1);
  if (columns != 0 && ncols != columns)
    throw std::invalid_argument("BondGraph: a neighbour index is beyond the " + std::to_string(columns) +
                                " columns");
  // The dual support by a counting sort; rows are visited in increasing order, so each dual
  // row comes out sorted by id.
  dual_offsets_.assign(ncols + 1, 0);
  for (const ParticleId j : families_.neighbors) ++dual_offsets_[j + 1];
  for (std::size_t j = 0; j < ncols; ++j) dual_offsets_[j + 1] += dual_offsets_[j];
  dual_cols_.resize(bonds());
  slot_.resize(bonds());
  std::vector<Offset> next(dual_offsets_.begin(), dual_offsets_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (Offset k = begin(i); k < end(i); ++k) {
      const Offset t = next[col(k)]++;
      dual_cols_[t] = static_cast<ParticleId>(i);
      slot_[k] = static_cast<std::uint32_t>(t - dual_offsets_[col(k)]);
    }
  alive_.assign(bonds(), 1);
  dual_alive_.assign(bonds(), 1);
  // Symmetric when every row's columns equal its dual row's (both sorted).
  symmetric_ = ncols == n;
  for (std::size_t i = 0; i < n && symmetric_; ++i) {
    symmetric_ = std::equal(families_.neighbors.begin() + begin(i), families_.neighbors.begin() + end(i),
                            dual_cols_.begin() + dual_begin(i), dual_cols_.begin() + dual_end(i));
  }
}

Offset BondGraph::find(std::size_t i, ParticleId j) const {
  if (i >= rows()) return -1;
  const auto first = families_.neighbors.begin() + begin(i), last = families_.neighbors.begin() + end(i);
  const auto it = std::lower_bound(first, last, j);  // rows are sorted by id
  return it != last && *it == j ? static_cast<Offset>(it - families_.neighbors.begin()) : -1;
}

bool BondGraph::break_bond(ParticleId i, ParticleId j) {
  bool changed = false;
  for (const auto& [a, b] : {std::pair{i, j}, std::pair{j, i}}) {
    const Offset k = find(static_cast<std::size_t>(a), b);
    if (k >= 0 && alive_[k]) {
      if (event_.empty()) event_.assign(alive_.size(), 0);  // an intact graph keeps none
      alive_[k] = 0;
      event_[k] = events_;
      dual_alive_[dual_entry(k)] = 0;
      ++broken_;
      changed = true;
    }
  }
  return changed;
}

std::vector<ParticleId> BondGraph::rows_touched(const std::vector<std::pair<ParticleId, ParticleId>>& breaks) const {
  std::vector<ParticleId> rows;
  for (const auto& [i, j] : breaks)
    for (const auto& [a, b] : {std::pair{i, j}, std::pair{j, i}}) {
      const Offset k = find(static_cast<std::size_t>(a), b);
      if (k >= 0 && alive_[k]) rows.push_back(a);
    }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  return rows;
}

std::size_t BondGraph::memory_bytes() const {
  return perinom::memory_bytes(families_) + dual_offsets_.size() * sizeof(Offset) +
         dual_cols_.size() * sizeof(ParticleId) + slot_.size() * sizeof(std::uint32_t) + alive_.size() +
         dual_alive_.size() + event_.size() * sizeof(std::uint32_t);
}

}  // namespace perinom

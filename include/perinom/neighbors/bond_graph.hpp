#pragma once
/// @file The bond graph: the families in CSR form, their dual support with the map from each
/// bond to its dual entry, and which bonds are alive. The one owner of the bond pattern: the
/// operators and stabilizations read it, and a broken bond is recorded here alone.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/neighbors/families.hpp"

namespace perinom {

/// Rows are the owned particles 0..rows()-1; a column (a neighbour) may be any local index
/// below columns(), so that ghost particles of a later domain split are columns without rows
/// and no operator changes. Bond k = (i, j) is the k-th entry of the row CSR (row i, column j);
/// its dual entry t (row j of the dual support, column i) lists it transposed. Broken bonds
/// keep their slots (so every per-bond array keeps its layout) and are marked dead.
class BondGraph {
 public:
  BondGraph() = default;
  /// The graph of these families, every bond alive. columns = 0 takes the particle count.
  explicit BondGraph(Families families, std::size_t columns = 0);

  std::size_t rows() const { return families_.particles(); }
  std::size_t columns() const { return dual_offsets_.size() - 1; }
  std::size_t bonds() const { return families_.bonds(); }
  /// The families as built (dead bonds included): the support radii and the pattern.
  const Families& families() const { return families_; }

  // Row CSR: the bonds of row i are begin(i) .. end(i)-1, sorted by column.
  Offset begin(std::size_t i) const { return families_.offsets[i]; }
  Offset end(std::size_t i) const { return families_.offsets[i + 1]; }
  ParticleId col(Offset k) const { return families_.neighbors[k]; }
  const std::vector<Offset>& offsets() const { return families_.offsets; }
  const std::vector<ParticleId>& cols() const { return families_.neighbors; }

  // Dual CSR: entry t of dual row j stands for the bond (dual_col(t), j); dual rows are
  // sorted by column.
  Offset dual_begin(std::size_t j) const { return dual_offsets_[j]; }
  Offset dual_end(std::size_t j) const { return dual_offsets_[j + 1]; }
  ParticleId dual_col(Offset t) const { return dual_cols_[t]; }
  /// The dual entry of bond k: the permutation from row order to dual order (4 bytes a bond:
  /// k's place within its dual row).
  Offset dual_entry(Offset k) const { return dual_offsets_[families_.neighbors[k]] + slot_[k]; }
  /// Whether the bond of dual entry t is alive.
  bool dual_alive(Offset t) const { return dual_alive_[t] != 0; }
  const std::vector<Offset>& dual_offsets() const { return dual_offsets_; }
  const std::vector<ParticleId>& dual_cols() const { return dual_cols_; }

  bool alive(Offset k) const { return alive_[k] != 0; }
  /// One byte per bond, 1 when alive (row order).
  const std::vector<std::uint8_t>& alive_mask() const { return alive_; }
  std::size_t broken() const { return broken_; }
  /// Visits the live bonds of row i in column order: f(k, j).
  template <class F>
  void for_each_live(std::size_t i, F&& f) const {
    for (Offset k = begin(i); k < end(i); ++k)
      if (alive_[k]) f(k, families_.neighbors[k]);
  }

  /// The position of bond (i, j), or -1 when j is not in H_i.
  Offset find(std::size_t i, ParticleId j) const;
  /// True when j in H_i exactly when i in H_j (a constant horizon radius).
  bool symmetric() const { return symmetric_; }
  /// The reverse (j, i) of bond k = (i, j), in O(1): a symmetric graph's dual row j lists
  /// the columns of row j in the same order. Only for symmetric graphs.
  Offset reverse(Offset k) const { return begin(families_.neighbors[k]) + slot_[k]; }

  /// Breaks (i, j) and (j, i), where they exist and are alive; true when a bond died. The
  /// bond is stamped with the current break event (below).
  bool break_bond(ParticleId i, ParticleId j);
  /// Starts the next break event: the bonds broken from now on carry its number (1, 2, ...),
  /// so that the order in which a crack grew can be read back (a model's break_bonds call is
  /// one event: each breaking round of a run).
  void begin_event() { ++events_; }
  std::uint32_t events() const { return events_; }
  /// The event bond k died in; 0 while it is alive, and for the body's initial cuts.
  std::uint32_t event(Offset k) const { return event_.empty() ? 0 : event_[k]; }
  /// The bonds broken so far are the body as built (precracks): their event becomes 0, and the
  /// events start again from 1.
  void settle_events() {
    std::fill(event_.begin(), event_.end(), 0u);
    events_ = 0;
  }
  /// The rows whose families a set of breaks changes (sorted, unique): i for a live (i, j),
  /// j for a live (j, i). Call it before the breaks, or pass what break_bond reported.
  std::vector<ParticleId> rows_touched(const std::vector<std::pair<ParticleId, ParticleId>>& breaks) const;

  std::size_t memory_bytes() const;

 private:
  Families families_;
  std::vector<Offset> dual_offsets_{0};
  std::vector<ParticleId> dual_cols_;
  std::vector<std::uint32_t> slot_;        // bond k -> its place in the dual row of its column
  std::vector<std::uint8_t> alive_, dual_alive_;  // per bond, in row and in dual order
  std::vector<std::uint32_t> event_;  // per bond: the event it died in (empty until a break)
  std::uint32_t events_ = 0;
  std::size_t broken_ = 0;
  bool symmetric_ = false;
};

}  // namespace perinom

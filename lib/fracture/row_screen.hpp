#pragma once
// Which rows of a bond graph can hold a bond whose measure reaches a threshold, found without a
// pass over the bonds (internal to lib/fracture): what keeps a criterion's per-step cost to the
// rows near breaking.
//
// From a snapshot state (u0, H0) to (u, H), with du = u - u0, a bond's measure moves by at most
//   stretch ratio    |xi + u_j - u_i| / |xi|:        |du_j - du_i| / |xi|
//   hourglass strain |u_j - u_i - H_i xi| / |xi|:    |du_j - du_i| / |xi| + |H_i - H0_i|_F
// (the triangle inequality, and |A xi| <= |A|_F |xi|). Over row i's family, |du_j - du_i| is
// at most the distance from du_i to the farthest corner of the box of du over the cells
// around i's cell (cells as wide as the longest bond hold every family), and |xi| is at least
// i's shortest bond. A row whose largest measure at the snapshot, r_i, plus that bound stays
// below the threshold holds no bond at it; only the other rows need their bonds read. The
// bound holds whatever changed in between (breaks, refreshed rows of G, detached particles),
// so the rows it keeps give the very bonds a full pass gives.
#include <cstddef>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/bond_graph.hpp"

namespace perinom::detail {

class RowScreen {
 public:
  /// The cells and each row's shortest bond, from the reference positions. The cloud must
  /// outlive the screen; bonds may die afterwards (the shortest over all bonds stays a bound).
  RowScreen(const PointCloud& cloud, const BondGraph& graph);

  bool taken() const { return !r_.empty(); }
  void clear() { r_.clear(); }
  /// The snapshot: u (N x d), H (N x d x d, or nullptr for a measure without the H term) and
  /// each row's largest measure over the bonds a criterion reads (N values).
  void take(const double* u, const double* H, std::vector<double> row_max);
  /// The rows, ascending, whose bound at (u, H) reaches `threshold` (less a relative 1e-6 for
  /// rounding). H must be given exactly when it was given to take().
  std::vector<ParticleId> rows_reaching(const double* u, const double* H, double threshold);
  /// The same at the snapshot's own state (no bound to add): the rows with r_i at the threshold.
  std::vector<ParticleId> rows_at_snapshot(double threshold) const;

 private:
  std::size_t cell_index(const int* c) const;
  void cell_boxes(const double* u);
  template <int D>
  void flag_rows(const double* u, const double* H, double limit);

  int d_;
  std::size_t particles_;
  int cells_[3] = {1, 1, 1};
  std::vector<std::size_t> cell_of_;         // per particle
  std::vector<std::size_t> cell_begin_;      // particles by cell, CSR
  std::vector<ParticleId> cell_members_;
  std::vector<double> inverse_shortest_;     // per row: 1 / its shortest bond
  std::vector<double> u0_, H0_, r_;          // the snapshot
  std::vector<double> box_, near_;           // per cell: du's box (lo, hi) and its neighbourhood's
  std::vector<unsigned char> flag_;          // per row: kept
};

}  // namespace perinom::detail

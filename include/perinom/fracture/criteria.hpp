#pragma once
/// @file Which bonds break (THEORY sec. 10), from a per-bond measure (bond_measures.hpp).
/// Breaking is irreversible: dead bonds are never selected again.
#include <functional>
#include <utility>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/neighbors/bond_graph.hpp"

namespace perinom {

using BondPair = std::pair<ParticleId, ParticleId>;

/// The live bonds (i, j) whose measure exceeds `threshold` strictly (a bond at exactly the
/// threshold holds): the stress criterion with bond stresses and f_t, the stretch criterion
/// with stretches and s_c.
std::vector<BondPair> bonds_above(const BondGraph& graph, const std::vector<double>& measure, double threshold);

/// The instability criterion of seed 002 (sec. 4): no bond breaks until the largest stretch of
/// a live bond reaches s_max; at that moment s_hg_max is fixed to the largest hourglass strain
/// of the live bonds, and from then on a live bond whose hourglass strain exceeds s_hg_max
/// breaks (none at the arming call itself: none exceeds the largest).
class InstabilityCriterion {
 public:
  /// Throws std::invalid_argument unless s_max > 0.
  explicit InstabilityCriterion(double s_max);
  /// The bonds to break for the current stretches and hourglass strains (per bond slot).
  std::vector<BondPair> select(const BondGraph& graph, const std::vector<double>& stretch,
                               const std::vector<double>& hourglass);
  /// The state change alone: arms when max_stretch (the largest live stretch) reaches s_max,
  /// fixing s_hg_max = max_hourglass() (called then only); returns armed(). A caller that
  /// selects the bonds itself (BondBreaking, one pass per step) uses this and threshold().
  bool arm(double max_stretch, const std::function<double()>& max_hourglass);
  bool armed() const { return armed_; }
  double s_max() const { return s_max_; }
  /// s_hg_max once armed (0 before).
  double threshold() const { return s_hg_max_; }
  /// Armed with s_hg_max = threshold, as an earlier run left it (a resumed checkpoint).
  void rearm(double threshold) { armed_ = true, s_hg_max_ = threshold; }

 private:
  double s_max_;
  bool armed_ = false;
  double s_hg_max_ = 0.0;
};

}  // namespace perinom

#include "perinom/fracture/criteria.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace perinom {
namespace {

// The largest measure over the live bonds (0 with none).
double live_max(const BondGraph& g, const std::vector<double>& m) {
  double top = 0.0;
  for (std::size_t k = 0; k < m.size(); ++k)
    if (g.alive(static_cast<Offset>(k))) top = std::max(top, m[k]);
  return top;
}

}  // namespace

std::vector<BondPair> bonds_above(const BondGraph& g, const std::vector<double>& measure, double threshold) {
  if (measure.size() != g.bonds())
    throw std::invalid_argument("bonds_above: " + std::to_string(measure.size()) + " values for " +
                                std::to_string(g.bonds()) + " bonds");
  std::vector<BondPair> out;
  for (std::size_t i = 0; i < g.rows(); ++i)
    for (Offset k = g.begin(i); k < g.end(i); ++k)
      if (g.alive(k) && measure[k] > threshold) out.emplace_back(static_cast<ParticleId>(i), g.col(k));
  return out;
}

InstabilityCriterion::InstabilityCriterion(double s_max) : s_max_(s_max) {
  if (!(s_max > 0.0)) throw std::invalid_argument("InstabilityCriterion: s_max must be positive");
}

bool InstabilityCriterion::arm(double max_stretch, const std::function<double()>& max_hourglass) {
  if (!armed_ && max_stretch >= s_max_) {
    armed_ = true;
    s_hg_max_ = max_hourglass();
  }
  return armed_;
}

std::vector<BondPair> InstabilityCriterion::select(const BondGraph& g, const std::vector<double>& stretch,
                                                   const std::vector<double>& hourglass) {
  if (!arm(live_max(g, stretch), [&] { return live_max(g, hourglass); })) return {};
  return bonds_above(g, hourglass, s_hg_max_);
}

}  // namespace perinom

#include "perinom/distributed/local_loading.hpp"

#include <stdexcept>

namespace perinom {

Loading local_loading(const Loading& whole, const LocalPart& part, int d) {
  if (whole.coupled_constraints())
    throw std::invalid_argument("local_loading: the whole loading's face-located constraints are coupled already "
                                "(rank_loading couples each rank's own)");
  if (!whole.value0.empty() || !whole.force0.empty())
    throw std::invalid_argument("local_loading: the whole loading has begun a stage (each rank's loading begins its own)");
  const auto owned = owned_index(part);
  Loading mine;
  mine.support_names = whole.support_names;
  mine.collocated = whole.collocated;
  for (std::size_t k = 0; k < whole.fixed.size(); ++k) {
    const auto at = owned.find(ParticleId(whole.fixed[k] / d));
    if (at == owned.end()) continue;
    mine.fixed.push_back(std::int64_t(at->second) * d + whole.fixed[k] % d);
    mine.value.push_back(whole.value[k]);
    if (!whole.rate.empty()) mine.rate.push_back(whole.rate[k]);
    if (!whole.support.empty()) mine.support.push_back(whole.support[k]);
  }
  // A rank holding no constraint of a loading with rates keeps an empty rate list: no rates.
  if (!whole.force.empty()) {
    mine.force.resize(part.owned * d);
    for (std::size_t p = 0; p < part.owned; ++p)
      for (int a = 0; a < d; ++a) mine.force[p * d + a] = whole.force[std::size_t(part.particles[p]) * d + a];
  }
  return mine;
}

}  // namespace perinom

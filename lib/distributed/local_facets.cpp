#include "perinom/distributed/local_facets.hpp"

#include <unordered_map>

namespace perinom {

LocalFacets local_facets(const BoundaryFacets& whole, const std::vector<FacetGroup>& groups, const LocalPart& part,
                         std::size_t rows) {
  std::unordered_map<ParticleId, std::size_t> local;
  for (std::size_t k = 0; k < rows && k < part.particles.size(); ++k) local[part.particles[k]] = k;
  LocalFacets out;
  BoundaryFacets& f = out.facets;
  const int d = whole.dim;
  f.dim = d;
  out.local_of.assign(whole.size(), -1);
  for (std::size_t k = 0; k < whole.size(); ++k) {
    const auto at = local.find(whole.particle[k]);
    if (at == local.end()) continue;
    out.local_of[k] = static_cast<std::int64_t>(f.size());
    f.particle.push_back(static_cast<ParticleId>(at->second));
    f.area.push_back(whole.area[k]);
    if (!whole.side.empty()) f.side.push_back(whole.side[k]);
    f.normal.insert(f.normal.end(), whole.normal.begin() + std::ptrdiff_t(k * d), whole.normal.begin() + std::ptrdiff_t((k + 1) * d));
    f.centroid.insert(f.centroid.end(), whole.centroid.begin() + std::ptrdiff_t(k * d),
                      whole.centroid.begin() + std::ptrdiff_t((k + 1) * d));
  }
  for (const auto& g : groups) {
    FacetGroup mine{g.name, {}};
    for (const std::size_t k : g.facets)
      if (out.local_of[k] >= 0) mine.facets.push_back(static_cast<std::size_t>(out.local_of[k]));
    out.groups.push_back(std::move(mine));
  }
  return out;
}

}  // namespace perinom

#include "perinom/geometry/body.hpp"

#include <algorithm>
#include <cmath>

namespace perinom {

const FacetGroup* find_group(const std::vector<FacetGroup>& groups, const std::string& name) {
  for (const auto& g : groups)
    if (g.name == name) return &g;
  return nullptr;
}

std::vector<ParticleId> group_particles(const FacetGroup& group, const BoundaryFacets& facets) {
  std::vector<ParticleId> ids;
  for (const std::size_t k : group.facets) ids.push_back(facets.particle[k]);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

void set_mean_size(Body& body, double thickness) {
  PointCloud& c = body.cloud;
  double volume = 0.0;
  for (const double v : c.volume) volume += v;
  const double per_particle = volume / (c.dim == 2 ? thickness : 1.0) / static_cast<double>(c.size());
  body.mean_size = std::pow(per_particle, 1.0 / c.dim);
  c.spacing.assign(c.dim, body.mean_size);
}

}  // namespace perinom

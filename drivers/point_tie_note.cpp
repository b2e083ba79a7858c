#include "point_tie_note.hpp"

#include <cstdio>
#include <set>
#include <vector>

#include "perinom/geometry/region.hpp"
#include "point_text.hpp"

namespace perinom::cli {

std::string point_tie_note(const Problem& p) {
  const Scene& s = p.scene;
  // A plate's point pressure takes the nearest node as a correspondence point region does.
  if ((s.model.type != "correspondence" && s.model.type != "thin_plate") || p.cloud.size() == 0) return "";
  std::vector<const BoundarySpec*> items;
  for (const auto& b : s.boundary) items.push_back(&b);
  for (const auto& stage : s.stages)
    for (const auto& b : stage.boundary) items.push_back(&b);
  std::string said;
  std::set<std::array<double, 3>> seen;  // a point repeated in every stage is said once
  for (const BoundarySpec* b : items) {
    if (!b->region.is_point || !seen.insert(b->region.point).second) continue;
    const double* at = b->region.point.data();
    const NearestParticle n = nearest_particle(p.cloud, at);
    const std::size_t tied = nearest_particles(p.cloud, at, n).size();
    if (tied < 2) continue;
    const std::string where = point_text(p.cloud.point(n.id), p.cloud.dim);
    char text[400];
    std::snprintf(text, sizeof text, "%s%s.region.point is as near %zu particles: particle %lld at (%s) holds it, %g m "
                  "from the point",
                  said.empty() ? "" : "; ", b->key.c_str(), tied, static_cast<long long>(n.id), where.c_str(),
                  n.distance);
    said += text;
  }
  if (said.empty()) return "";
  return said + " (on a tie the lowest-numbered particle is taken; a point on a particle, or a dx that puts one there, "
                "holds the point itself)";
}

}  // namespace perinom::cli

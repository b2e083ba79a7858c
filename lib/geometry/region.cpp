#include "perinom/geometry/region.hpp"

#include <cmath>
#include <map>

namespace perinom {

bool parse_side(const std::string& name, int dim, Side& side) {
  const int vertical = dim - 1;
  const std::map<std::string, Side> names = {
      {"left", {0, false}},         {"right", {0, true}},        {"xmin", {0, false}},
      {"xmax", {0, true}},          {"ymin", {1, false}},        {"ymax", {1, true}},
      {"bottom", {vertical, false}}, {"top", {vertical, true}}, {"zmin", {2, false}},
      {"zmax", {2, true}},          {"front", {1, false}},       {"back", {1, true}}};
  const auto it = names.find(name);
  if (it == names.end()) return false;
  if (it->second.axis >= dim) return false;
  if (dim == 2 && (name == "front" || name == "back")) return false;
  side = it->second;
  return true;
}

std::vector<ParticleId> select(const Region& region, const BoxGeometry& box,
                               const PointCloud& cloud) {
  std::vector<ParticleId> ids;
  const int d = cloud.dim;
  if (region.is_point) {
    double best = INFINITY;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      double r2 = 0.0;
      for (int a = 0; a < d; ++a) r2 += (cloud.x[i * d + a] - region.point[a]) * (cloud.x[i * d + a] - region.point[a]);
      if (r2 < best) best = r2, ids.assign(1, static_cast<ParticleId>(i));
    }
    return ids;
  }
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double* p = cloud.point(i);
    bool in = true;
    if (region.is_side) {
      const int a = region.side.axis;
      const double h = cloud.spacing[a];
      in = region.side.at_max ? p[a] > box.max[a] - h : p[a] < box.min[a] + h;
    } else {
      for (int a = 0; a < d; ++a) in = in && p[a] >= region.min[a] && p[a] <= region.max[a];
    }
    if (in) ids.push_back(static_cast<ParticleId>(i));
  }
  return ids;
}

std::array<double, 3> outward_normal(const Side& side) {
  std::array<double, 3> n{0, 0, 0};
  n[side.axis] = side.at_max ? 1.0 : -1.0;
  return n;
}

}  // namespace perinom

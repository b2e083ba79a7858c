#include "perinom/geometry/region.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

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

namespace {

double distance2(const PointCloud& cloud, std::size_t i, const double* point) {
  double r2 = 0.0;
  for (int a = 0; a < cloud.dim; ++a) r2 += (cloud.x[i * cloud.dim + a] - point[a]) * (cloud.x[i * cloud.dim + a] - point[a]);
  return r2;
}

}  // namespace

NearestParticle nearest_particle(const PointCloud& cloud, const double* point) {
  double best = INFINITY;
  std::size_t arg = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double r2 = distance2(cloud, i, point);
    if (r2 < best) best = r2, arg = i;
  }
  // The spacing: the distance to its d-th nearest neighbour, a lattice's spacing even at a
  // corner, which a sliver element's one close neighbour does not shrink.
  std::vector<double> closest(cloud.dim, INFINITY);  // ascending
  for (std::size_t j = 0; j < cloud.size(); ++j) {
    if (j == arg) continue;
    double r2 = distance2(cloud, j, cloud.point(arg));
    for (double& c : closest)
      if (r2 < c) std::swap(r2, c);
  }
  double spacing2 = INFINITY;
  for (const double c : closest)
    if (c < INFINITY) spacing2 = c;  // a cloud of fewer particles: its farthest
  NearestParticle n{static_cast<ParticleId>(arg), std::sqrt(best), std::sqrt(spacing2)};
  // On a tie (to 1e-9 of the spacing) the lowest index, not whichever rounding put nearer.
  if (const std::vector<ParticleId> tied = nearest_particles(cloud, point, n); !tied.empty()) n.id = tied.front();
  return n;
}

std::vector<ParticleId> nearest_particles(const PointCloud& cloud, const double* point, const NearestParticle& n) {
  const double reach = n.distance + 1e-9 * (std::isfinite(n.spacing) ? n.spacing : n.distance);
  std::vector<ParticleId> ids;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (std::sqrt(distance2(cloud, i, point)) <= reach) ids.push_back(static_cast<ParticleId>(i));
  return ids;
}

std::string outside_body(const NearestParticle& n, const PointCloud& cloud) {
  if (!(n.distance > 2.0 * n.spacing)) return "";
  std::ostringstream msg;
  msg << "is " << n.distance << " m from the nearest particle (" << n.distance / n.spacing
      << " of its spacings; particle " << n.id << " at (";
  for (int a = 0; a < cloud.dim; ++a) msg << (a ? ", " : "") << cloud.x[n.id * cloud.dim + a];
  msg << ")): outside the body or in a hole";
  return msg.str();
}

std::string outside_box(const BoxGeometry& box, const double* point, double slack) {
  double side = 0.0, worst = 0.0;
  int axis = -1;
  bool above = false;
  for (int a = 0; a < box.dim; ++a) side = std::max(side, box.max[a] - box.min[a]);
  for (int a = 0; a < box.dim; ++a)
    for (const bool up : {false, true}) {
      const double past = up ? point[a] - box.max[a] : box.min[a] - point[a];
      if (past > worst) worst = past, axis = a, above = up;
    }
  if (!(worst > std::max(1e-9 * side, slack))) return "";
  std::ostringstream msg;
  msg << "lies " << worst << " m outside geometry.box (past its " << (above ? "max " : "min ") << "xyz"[axis]
      << " = " << (above ? box.max[axis] : box.min[axis]) << " m)";
  return msg.str();
}

std::string inside_hole(const BoxGeometry& box, const double* point) {
  for (std::size_t k = 0; k < box.holes.size(); ++k) {
    Hole inner = box.holes[k];
    inner.radius *= 1.0 - 1e-6;
    if (!inner.contains(point, box.dim)) continue;
    std::ostringstream msg;
    msg << "lies inside hole " << k << " (centre (";
    for (int a = 0; a < box.dim; ++a) msg << (a ? ", " : "") << box.holes[k].center[a];
    msg << "), radius " << box.holes[k].radius << " m)";
    return msg.str();
  }
  return "";
}

std::vector<ParticleId> select(const Region& region, const BoxGeometry& box,
                               const PointCloud& cloud) {
  std::vector<ParticleId> ids;
  const int d = cloud.dim;
  if (region.is_point) {
    if (cloud.size() > 0) ids.push_back(nearest_particle(cloud, region.point.data()).id);
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

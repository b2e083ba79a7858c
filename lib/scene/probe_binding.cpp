// Where a probe reads: the particle nearest a point probe's point, the particles along a line
// probe's segment; points off the body and lines that meet no particle are refused by key.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "perinom/core/error.hpp"
#include "perinom/geometry/region.hpp"
#include "perinom/scene/problem.hpp"

namespace perinom {

BoundProbe bind_probe(const ProbeSpec& p, const PointCloud& cloud, const BoxGeometry* box) {
  const int d = cloud.dim;
  BoundProbe b{p, {}, {}};
  if (!p.is_line) {
    // A thousandth of a spacing off is a coordinate copied to six digits, not a point off the body.
    const double slack = cloud.spacing.empty() ? 0.0 : 1e-3 * *std::max_element(cloud.spacing.begin(), cloud.spacing.end());
    if (const std::string off = box ? outside_box(*box, p.point.data(), slack) : ""; !off.empty())
      throw InputError(p.where + ".point: probe '" + p.name + "' " + off +
                       "; a point probe reads the particle nearest its point, and with reconstruct extrapolates "
                       "from it past the surface (a bar in uniform tension read 3% high 1.2 spacings beyond its "
                       "end): put the point on the body's surface or inside it");
    if (const std::string hole = box ? inside_hole(*box, p.point.data()) : ""; !hole.empty())
      throw InputError(p.where + ".point: probe '" + p.name + "' " + hole +
                       "; a point probe reads the particle nearest its point, here one on the hole's edge");
    const NearestParticle nearest = nearest_particle(cloud, p.point.data());
    const std::string outside = outside_body(nearest, cloud);
    if (!outside.empty())
      throw InputError(p.where + ".point: probe '" + p.name + "' " + outside +
                       "; a point probe reads the particle nearest its point");
    b.particles.push_back(nearest.id);
    return b;
  }
  double len2 = 0.0;
  for (int a = 0; a < d; ++a) len2 += std::pow(p.to[a] - p.from[a], 2);
  if (!(len2 > 0.0)) throw InputError(p.where + ".line: probe '" + p.name + "' has from equal to to");
  const double half = 0.5 * *std::max_element(cloud.spacing.begin(), cloud.spacing.end());
  std::vector<std::pair<double, ParticleId>> hits;
  double closest = INFINITY;  // squared, for the error when none is within half a spacing
  std::size_t nearest = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    double t = 0.0;
    for (int a = 0; a < d; ++a) t += (cloud.x[i * d + a] - p.from[a]) * (p.to[a] - p.from[a]);
    t = std::clamp(t / len2, 0.0, 1.0);
    double r2 = 0.0;
    for (int a = 0; a < d; ++a)
      r2 += std::pow(cloud.x[i * d + a] - (p.from[a] + t * (p.to[a] - p.from[a])), 2);
    if (r2 <= half * half * (1.0 + 1e-9)) hits.emplace_back(t * std::sqrt(len2), static_cast<ParticleId>(i));
    if (r2 < closest) closest = r2, nearest = i;
  }
  if (hits.empty()) {
    // A 3-D line through the centre of a bar an even number of particles across passes the
    // four nearest rows at sqrt(2) dx / 2: "meets no particle" alone read as a wrong line.
    std::ostringstream msg;
    msg << p.where << ".line: probe '" << p.name << "' meets no particle: a line reads the particles within half a "
        << "spacing (" << half << " m) of it, and the nearest, particle " << nearest << " at (";
    for (int a = 0; a < d; ++a) msg << (a ? ", " : "") << cloud.x[nearest * d + a];
    msg << "), is " << std::sqrt(closest) << " m from it; a line between rows of particles (through the middle "
        << "of a body an even number of particles across) meets none: move it onto a row";
    throw InputError(msg.str());
  }
  std::sort(hits.begin(), hits.end());
  for (const auto& h : hits) {
    b.along.push_back(h.first);
    b.particles.push_back(h.second);
  }
  return b;
}

}  // namespace perinom

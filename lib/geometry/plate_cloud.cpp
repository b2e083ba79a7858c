#include "perinom/geometry/plate_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

/// The image of lattice index g on an axis of n nodes, and the sign it picks up; false when
/// g lies beyond an edge without ghosts.
bool image_of(long g, long n, EdgeSupport lo, EdgeSupport hi, long& image, double& sign) {
  image = g;
  sign = 1.0;
  if (g >= 0 && g < n) return true;
  const EdgeSupport e = g < 0 ? lo : hi;
  if (e == EdgeSupport::free) return false;
  image = g < 0 ? -g : 2 * (n - 1) - g;
  sign = e == EdgeSupport::simply_supported ? -1.0 : 1.0;
  return true;
}

}  // namespace

std::vector<ParticleId> PlateCloud::edge_nodes(int e) const {
  std::vector<ParticleId> ids;
  const int axis = e / 2;
  const long fixed = e % 2 ? nodes[axis] - 1 : 0;
  const long other = nodes[1 - axis];
  for (long k = 0; k < other; ++k) {
    const long i = axis == 0 ? fixed : k, j = axis == 0 ? k : fixed;
    ids.push_back(static_cast<ParticleId>(j * nodes[0] + i));
  }
  return ids;
}

PlateCloud make_plate_cloud(const BoxGeometry& box, double dx, const PlateEdges& edges, int layers) {
  if (box.dim != 2) throw InputError("a thin plate is two-dimensional");
  PlateCloud p;
  PointCloud& c = p.cloud;
  c.dim = 2;
  c.dx = dx;
  c.spacing.resize(2);
  for (int a = 0; a < 2; ++a) {
    const double length = box.max[a] - box.min[a];
    const long cells = std::lround(length / dx);
    if (cells < 2 || cells <= layers)
      throw InputError("the plate has " + std::to_string(cells) + " cells along " + (a ? "y" : "x") +
                       "; a thin plate needs at least " + std::to_string(std::max(2, layers + 1)) +
                       " (2, and more than its " + std::to_string(layers) + " ghost layers)");
    if (cells > 40000) throw InputError("the plate holds more than 40000 cells per side (check discretization.dx)");
    p.nodes[a] = cells + 1;
    c.spacing[a] = length / cells;
  }
  const double cell = c.spacing[0] * c.spacing[1];
  const long nx = p.nodes[0], ny = p.nodes[1];
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      c.x.push_back(box.min[0] + i * c.spacing[0]);
      c.x.push_back(box.min[1] + j * c.spacing[1]);
      const double fx = (i == 0 || i == nx - 1) ? 0.5 : 1.0, fy = (j == 0 || j == ny - 1) ? 0.5 : 1.0;
      p.area.push_back(cell * fx * fy);
    }
  p.physical = p.area.size();
  for (long j = -layers; j < ny + layers; ++j)
    for (long i = -layers; i < nx + layers; ++i) {
      if (i >= 0 && i < nx && j >= 0 && j < ny) continue;
      long ii, jj;
      double sx, sy;
      if (!image_of(i, nx, edges[0], edges[1], ii, sx) || !image_of(j, ny, edges[2], edges[3], jj, sy)) continue;
      c.x.push_back(box.min[0] + i * c.spacing[0]);
      c.x.push_back(box.min[1] + j * c.spacing[1]);
      p.image.push_back(static_cast<ParticleId>(jj * nx + ii));
      p.sign.push_back(sx * sy);
    }
  c.volume.assign(c.x.size() / 2, cell * box.thickness);
  return p;
}

PlateCloud sub_plate(const PlateCloud& whole, const std::vector<ParticleId>& nodes) {
  PlateCloud p;
  std::vector<std::int64_t> local(whole.physical, -1);
  std::vector<ParticleId> kept = nodes;  // the nodes, then the mirrors of those among them
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    local.at(nodes[k]) = std::int64_t(k);
    p.area.push_back(whole.area[nodes[k]]);
  }
  p.physical = nodes.size();
  for (std::size_t g = 0; g < whole.image.size(); ++g) {
    if (local[whole.image[g]] < 0) continue;
    kept.push_back(static_cast<ParticleId>(whole.physical + g));
    p.image.push_back(static_cast<ParticleId>(local[whole.image[g]]));
    p.sign.push_back(whole.sign[g]);
  }
  p.cloud = subcloud(whole.cloud, kept);
  return p;
}

}  // namespace perinom

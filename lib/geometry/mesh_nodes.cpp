#include "perinom/geometry/mesh_nodes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <unordered_map>

#include "perinom/core/error.hpp"

namespace perinom {

std::vector<std::size_t> used_nodes(const GmshMesh& mesh, int dim) {
  std::vector<char> used(mesh.nodes(), 0);
  for (std::size_t e = 0; e < mesh.elements(); ++e)
    if (gmsh_element_shape(mesh.type[e]).first == dim)
      for (std::size_t k = mesh.offsets[e]; k < mesh.offsets[e + 1]; ++k) used[mesh.node_index[k]] = 1;
  std::vector<std::size_t> nodes;
  for (std::size_t v = 0; v < used.size(); ++v)
    if (used[v]) nodes.push_back(v);
  return nodes;
}

void check_planar(const GmshMesh& mesh, const std::vector<std::size_t>& nodes) {
  double lo = INFINITY, hi = -INFINITY, extent = 0.0;
  for (const std::size_t v : nodes) {
    lo = std::min(lo, mesh.x[3 * v + 2]), hi = std::max(hi, mesh.x[3 * v + 2]);
    extent = std::max({extent, std::abs(mesh.x[3 * v]), std::abs(mesh.x[3 * v + 1])});
  }
  if (hi - lo > 1e-12 * extent) {
    char span[240];  // (%g: a span of 2e-9 m printed by std::to_string read 0.000000 to 0.000000)
    std::snprintf(span, sizeof span,
                  "the nodes of its elements: z spans %.6g to %.6g m, more than 1e-12 of its extent %.6g m",
                  lo, hi, extent);
    throw InputError(std::string("a 2-D scene needs a mesh in a plane z = const (") + span + ")");
  }
}

namespace {

using Cell = std::array<std::int64_t, 3>;

struct CellHash {
  std::size_t operator()(const Cell& c) const {
    std::size_t h = 0;
    for (const auto v : c) h = h * 1000003u ^ std::hash<std::int64_t>()(v);
    return h;
  }
};

}  // namespace

void check_distinct_nodes(const GmshMesh& mesh, const std::vector<std::size_t>& nodes) {
  if (nodes.size() < 2) return;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const std::size_t v : nodes)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], mesh.x[3 * v + a]), hi[a] = std::max(hi[a], mesh.x[3 * v + a]);
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const double tolerance = 1e-8 * diagonal;
  if (!(tolerance > 0.0)) return;  // one point: the elements' zero volume is refused after
  auto cell_of = [&](std::size_t v) {
    Cell c{};
    for (int a = 0; a < 3; ++a) c[a] = static_cast<std::int64_t>(std::floor((mesh.x[3 * v + a] - lo[a]) / tolerance));
    return c;
  };
  std::unordered_map<Cell, std::vector<std::size_t>, CellHash> grid;
  grid.reserve(nodes.size());
  for (const std::size_t v : nodes) grid[cell_of(v)].push_back(v);
  for (const std::size_t v : nodes) {
    const Cell c = cell_of(v);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (const std::size_t w : it->second) {
            if (w <= v) continue;  // each pair once
            double d2 = 0.0;
            for (int a = 0; a < 3; ++a) d2 += (mesh.x[3 * v + a] - mesh.x[3 * w + a]) * (mesh.x[3 * v + a] - mesh.x[3 * w + a]);
            if (d2 > tolerance * tolerance) continue;
            char text[400];
            std::snprintf(text, sizeof text,
                          "nodes %zu and %zu are both at (%.9g, %.9g, %.9g) (within 1e-8 of the mesh's extent, "
                          "gmsh's Geometry.Tolerance): the elements on either side share no face, a seam the "
                          "body would open along; merge duplicate nodes (gmsh: 'Coherence Mesh;' in the .geo, or "
                          "gmsh.model.mesh.removeDuplicateNodes()), or cut a crack with precracks",
                          std::min(mesh.tag[v], mesh.tag[w]), std::max(mesh.tag[v], mesh.tag[w]), mesh.x[3 * v],
                          mesh.x[3 * v + 1], mesh.x[3 * v + 2]);
            throw InputError(text);
          }
        }
  }
}

}  // namespace perinom

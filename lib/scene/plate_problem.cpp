// A thin_plate scene built: the plate's nodes and ghosts, families, the ThinPlateModel, the
// edge conditions and the pressure, the probes. No correspondence operator is assembled.
#include <algorithm>
#include <cmath>

#include "perinom/core/error.hpp"
#include "perinom/scene/plate_part.hpp"
#include "scene_loading.hpp"

namespace perinom {
namespace {

/// Ghost layers that cover every physical node's family: delta over the smallest spacing for
/// radius families; for k nearest, a guess checked once the families exist.
int ghost_layers(const Scene& s) {
  const auto& g = s.geometry;
  const double dx = s.discretization.dx;
  double h = INFINITY;
  for (int a = 0; a < 2; ++a) {
    const double L = g.max[a] - g.min[a];
    h = std::min(h, L / std::max(1L, std::lround(L / dx)));
  }
  if (s.discretization.horizon_neighbors > 0)
    return static_cast<int>(std::ceil(std::sqrt(s.discretization.horizon_neighbors / M_PI))) + 1;
  return static_cast<int>(std::floor(s.discretization.horizon_ratio * dx / h * (1.0 + 1e-9)));
}

}  // namespace

PlateFrame plate_frame(const Scene& s) {
  PlateFrame out;
  Problem& p = out.problem;
  p.scene = s;
  PlateEdges edges{EdgeSupport::free, EdgeSupport::free, EdgeSupport::free, EdgeSupport::free};
  for (const auto& b : s.boundary)
    if (b.support) edges[b.region.side.axis * 2 + (b.region.side.at_max ? 1 : 0)] = *b.support;
  out.layers = ghost_layers(s);
  PlateCloud& plate = out.plate;
  try {
    plate = make_plate_cloud(s.geometry, s.discretization.dx, edges, out.layers);
  } catch (const InputError& e) {
    throw InputError(s.source + ": discretization.dx: " + e.what());
  }
  // The solvers see the physical nodes, with their quadrature volumes.
  p.cloud.dim = 2;
  p.cloud.dx = s.discretization.dx;
  p.cloud.spacing = plate.cloud.spacing;
  p.cloud.x.assign(plate.cloud.x.begin(), plate.cloud.x.begin() + 2 * plate.physical);
  p.cloud.volume = plate.area;
  for (double& v : p.cloud.volume) v *= s.geometry.thickness;
  // w = 0 on the supported edges; the pressure q as the nodal force q A_i.
  for (int e = 0; e < 4; ++e)
    if (edges[e] != EdgeSupport::free)
      for (const ParticleId i : plate.edge_nodes(e)) p.loading.fix(i, 0.0);
  std::vector<std::uint8_t> held(plate.physical, 0);
  for (const auto dof : p.loading.fixed) held[dof] = 1;
  for (const auto& b : s.boundary) {
    if (!b.pressure) continue;
    // A side is its edge's nodes: the plate's nodes sit on the edges, so the rule of a
    // particle lattice (the layer within one spacing of the face) met the next row at exactly
    // one spacing and took it or not by rounding (a pressure on `top` moved the free edge by
    // 4.1, 5.9, 8.0 and 1.1 um at dx = 12.5, 50, 25 and 10 mm).
    // A point more than two spacings off the plate is refused as a correspondence scene's is
    // (a point load 2.1 m off a 0.5 m plate landed on its corner node, exit 0).
    const auto ids = b.region.is_side ? plate.edge_nodes(b.region.side.axis * 2 + (b.region.side.at_max ? 1 : 0))
                                      : detail::select_region(b.region, s, p.cloud, b.where);
    if (ids.empty()) throw InputError(b.where + ".region: selects no particle");
    // A pressure on supported edge nodes only goes whole into the supports (the centre read
    // w = 0, exit 0); a correspondence scene refuses the like (scene_loading.cpp).
    if (std::all_of(ids.begin(), ids.end(), [&](ParticleId i) { return held[i] != 0; }))
      throw InputError(b.where + ".pressure: acts only on nodes of supported edges, held at w = 0: the whole load goes "
                                 "into the supports and bends nothing (a pressure over the plate: region: all)");
    if (p.loading.force.empty()) p.loading.force.assign(plate.physical, 0.0);
    for (const auto i : ids) p.loading.force[i] += *b.pressure * plate.area[i];
  }
  for (const auto& probe : s.probes) p.probes.push_back(bind_probe(probe, p.cloud));
  ThinPlateOptions& opt = out.options;
  opt.E = s.material.E;
  opt.nu = s.material.nu;
  opt.density = s.material.density;
  opt.thickness = s.geometry.thickness;
  opt.influence = s.discretization.weight;
  opt.stabilization = s.model.stabilization;
  opt.edges = edges;
  return out;
}

Families plate_families(const Scene& s, const PlateFrame& frame, const PlateCloud& plate, std::size_t rows) {
  Families families = scene_families(s, plate.cloud);
  // A family reaches no ghost beyond the last layer while its radius stays below the next one.
  const double reach = (frame.layers + 1) * std::min(plate.cloud.spacing[0], plate.cloud.spacing[1]) * (1.0 - 1e-9);
  for (std::size_t i = 0; i < std::min(rows, plate.physical); ++i)
    if (families.support[i] >= reach)
      throw InputError(s.source + ": " + horizon_key(s) + ": the families reach beyond the plate's " +
                       std::to_string(frame.layers) + " ghost layers (use fewer neighbours)");
  return families;
}

std::unique_ptr<ThinPlateModel> plate_model(const Scene& s, PlateCloud plate, const Families& families,
                                            const ThinPlateOptions& opt) {
  const PointCloud lattice = plate.cloud;  // (for the message: the plate is moved into the model)
  try {
    return std::make_unique<ThinPlateModel>(std::move(plate), families, opt);
  } catch (const InputError& e) {
    throw InputError(horizon_error(s, lattice, e.what()));
  }
}

Problem build_plate_problem(const Scene& s, PhaseTimer* timer) {
  if (timer) timer->start("discretization");
  PlateFrame frame = plate_frame(s);
  Problem p = std::move(frame.problem);
  const Families families = plate_families(s, frame, frame.plate, frame.plate.physical);
  // The physical nodes' bonds (a ghost's family is fitted but carries no energy): what the
  // ranks of a distributed run sum over their owned nodes.
  p.bonds = std::size_t(families.offsets[frame.plate.physical]);
  if (timer) timer->start("operators");
  p.model = plate_model(s, std::move(frame.plate), families, frame.options);
  if (timer) timer->stop();
  return p;
}

}  // namespace perinom

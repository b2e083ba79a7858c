// Boundary conditions turned into a Loading (scene_loading.hpp).
#include "scene_loading.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include <array>

#include "perinom/core/error.hpp"
#include "perinom/geometry/region.hpp"

namespace perinom::detail {
namespace {

/// Adds the nodal forces of a uniform traction t on a side: work-consistent loads at the
/// side's boundary facets when there is a trace (the consistent formulation), else the
/// classical body force on the outer layer (force = t * V_i / layer thickness).
void add_side_traction(const Side& side, const std::vector<ParticleId>& ids, const double* t,
                       const PointCloud& cloud, const BoundaryTrace* trace, std::vector<double>& force) {
  const int d = cloud.dim;
  if (trace && !trace->empty()) {
    const auto& f = trace->facets();
    for (std::size_t k = 0; k < f.size(); ++k)
      if (f.side[k] == 2 * side.axis + (side.at_max ? 1 : 0)) trace->add_traction(k, t, force.data());
    return;
  }
  const double h = cloud.spacing[side.axis];
  for (const auto i : ids)
    for (int a = 0; a < d; ++a) force[i * d + a] += t[a] * cloud.volume[i] / h;
}

/// Adds the forces of a traction t plus a pressure p (along each facet's own outward normal)
/// on the facets of a group: work-consistent loads through the trace, or, without one (the
/// classical formulation), the facet's force A_k t_k on its owner.
void add_group_traction(const FacetGroup& group, const double* t, double p, const BoundaryData& boundary,
                        std::vector<double>& force) {
  const BoundaryFacets& f = *boundary.facets;
  const int d = f.dim;
  for (const std::size_t k : group.facets) {
    double tk[3] = {0, 0, 0};
    for (int a = 0; a < d; ++a) tk[a] = t[a] - p * f.normal[k * d + a];
    if (boundary.trace && !boundary.trace->empty()) {
      boundary.trace->add_traction(k, tk, force.data());
      continue;
    }
    for (int a = 0; a < d; ++a) force[f.particle[k] * d + a] += f.area[k] * tk[a];
  }
}

/// The traction on a side: `traction` (if given) less `pressure` along the outward normal.
std::array<double, 3> side_load(const Side& side, const std::optional<std::array<double, 3>>& traction, double pressure,
                                int d) {
  std::array<double, 3> t{0, 0, 0};
  const auto n = outward_normal(side);
  for (int a = 0; a < d; ++a) t[a] = (traction ? (*traction)[a] : 0.0) - pressure * n[a];
  return t;
}

/// The group a boundary item names; errors name the key and list the groups there are.
const FacetGroup& region_group(const BoundarySpec& b, const BoundaryData& boundary) {
  const FacetGroup* g = boundary.groups ? find_group(*boundary.groups, b.region.group) : nullptr;
  if (!g) {
    std::string known;
    if (boundary.groups)
      for (const auto& h : *boundary.groups) known += (known.empty() ? "" : ", ") + h.name;
    throw InputError(b.where + ".region.group: unknown group '" + b.region.group + "' (" +
                     (known.empty() ? "the body has no boundary groups" : "the body's groups: " + known) + ")");
  }
  if (g->facets.empty())
    throw InputError(b.where + ".region.group: group '" + b.region.group + "' holds no boundary facet");
  return *g;
}

}  // namespace

std::vector<ParticleId> select_region(const Region& region, const Scene& s, const PointCloud& cloud,
                                      const std::string& where) {
  if (region.is_point) {
    if (const std::string hole = inside_hole(s.geometry, region.point.data()); !hole.empty())
      throw InputError(where + ".region.point: the point " + hole + "; a point region holds the particle nearest its point, "
                               "here one on the hole's edge");
    const NearestParticle nearest = nearest_particle(cloud, region.point.data());
    const std::string outside = outside_body(nearest, cloud);
    if (!outside.empty())
      throw InputError(where + ".region.point: the point " + outside + "; a point region holds the particle nearest its point");
    return {nearest.id};
  }
  const std::vector<ParticleId> ids = select(region, s.geometry, cloud);
  if (ids.empty()) throw InputError(where + ".region: selects no particle");
  return ids;
}

namespace {

/// One boundary item's share of the external force: its nonzero entries (dof, force).
struct ItemLoad {
  const BoundarySpec* item;
  std::vector<std::pair<std::size_t, double>> force;
};

/// "stages.1.boundary.0" as messages name it: "stages[1].boundary[0]".
std::string bracketed(const std::string& key) {
  std::string out;
  for (std::size_t i = 0; i < key.size(); ++i) {
    if (key[i] == '.' && i + 1 < key.size() && std::isdigit(static_cast<unsigned char>(key[i + 1]))) {
      std::size_t j = i + 1;
      while (j < key.size() && std::isdigit(static_cast<unsigned char>(key[j]))) ++j;
      out += "[" + key.substr(i + 1, j - i - 1) + "]";
      i = j - 1;
    } else {
      out += key[i];
    }
  }
  return out;
}

/// A traction or pressure that acts only on components held at their particles (`at: layer`)
/// goes whole into the supports' reactions and moves nothing: refused, naming the item and the
/// support that takes it (a face-located hold passes a load on through its reconstruction).
void refuse_held_loads(const std::vector<ItemLoad>& loads, const Loading& load, const FaceOf& face_of,
                       std::size_t dofs) {
  if (loads.empty()) return;
  std::vector<std::int64_t> held(dofs, -1);  // dof -> its constraint, or -1
  for (std::size_t k = 0; k < load.fixed.size(); ++k)
    if (face_of.find(load.fixed[k]) == face_of.end()) held[load.fixed[k]] = static_cast<std::int64_t>(k);
  for (const ItemLoad& l : loads) {
    double total = 0.0, absorbed = 0.0;
    int support = -1;
    for (const auto& [dof, f] : l.force) {
      total += std::abs(f);
      if (held[dof] < 0) continue;
      absorbed += std::abs(f);
      if (!load.support.empty() && load.support[held[dof]] >= 0) support = load.support[held[dof]];
    }
    if (total == 0.0 || absorbed < total) continue;
    const std::string by = support >= 0 ? " (by " + bracketed(load.support_names[support]) + ")" : "";
    throw InputError(l.item->where + (l.item->traction ? ".traction" : ".pressure") +
                     ": acts only on components held at their particles" + by +
                     ": the whole load goes into the support's reaction and moves nothing (hold those components "
                     "elsewhere, or at the face: at: face)");
  }
}

}  // namespace

Loading make_loading(const Scene& s, const std::vector<BoundarySpec>& boundary, const PointCloud& cloud,
                     FaceOf& face_of, const BoundaryData& data) {
  const int d = s.dim;
  Loading load;
  std::vector<ItemLoad> loads;
  for (const auto& b : boundary) {
    const FacetGroup* group = b.region.is_group() ? &region_group(b, data) : nullptr;
    const auto ids = group ? group_particles(*group, *data.facets) : select_region(b.region, s, cloud, b.where);
    if (ids.empty()) throw InputError(b.where + ".region: selects no particle");
    // A group's face constraint acts at the largest facet the particle owns in the group.
    std::map<ParticleId, std::size_t> facet_of;
    if (group)
      for (const std::size_t k : group->facets) {
        const auto it = facet_of.find(data.facets->particle[k]);
        if (it == facet_of.end() || data.facets->area[k] > data.facets->area[it->second])
          facet_of[data.facets->particle[k]] = k;
      }
    auto given = [d](const std::array<std::optional<double>, 3>& v) {
      return std::any_of(v.begin(), v.begin() + d, [](const std::optional<double>& x) { return x.has_value(); });
    };
    const bool constrains = std::any_of(b.fix.begin(), b.fix.begin() + d, [](bool f) { return f; }) ||
                            given(b.displacement) || given(b.velocity);
    const int support = constrains ? load.add_support(b.key) : -1;
    for (int a = 0; a < d; ++a) {
      if (!b.fix[a] && !b.displacement[a] && !b.velocity[a]) continue;
      for (const auto i : ids) {
        const std::int64_t dof = static_cast<std::int64_t>(i) * d + a;
        load.fix(dof, b.displacement[a].value_or(0.0), support, b.velocity[a].value_or(0.0));
        if (b.at_face) face_of[dof] = {b.region.side, group ? static_cast<std::int64_t>(facet_of.at(i)) : -1};
        else face_of.erase(dof);
      }
    }
    if (!b.traction && !b.pressure) continue;
    if (load.force.empty()) load.force.assign(cloud.size() * d, 0.0);
    if (b.pressure && load.pressure_force.empty()) load.pressure_force.assign(cloud.size() * d, 0.0);
    std::vector<double> own(load.force.size(), 0.0);
    if (group) {
      const double zero[3] = {0, 0, 0};
      add_group_traction(*group, b.traction ? b.traction->data() : zero, b.pressure.value_or(0.0), data, own);
      if (b.pressure) add_group_traction(*group, zero, *b.pressure, data, load.pressure_force);
    } else {
      const Side& side = b.region.side;
      add_side_traction(side, ids, side_load(side, b.traction, b.pressure.value_or(0.0), d).data(), cloud, data.trace,
                        own);
      if (b.pressure)
        add_side_traction(side, ids, side_load(side, std::nullopt, *b.pressure, d).data(), cloud, data.trace,
                          load.pressure_force);
    }
    ItemLoad item{&b, {}};
    for (std::size_t k = 0; k < own.size(); ++k)
      if (own[k] != 0.0) load.force[k] += own[k], item.force.emplace_back(k, own[k]);
    loads.push_back(std::move(item));
  }
  refuse_held_loads(loads, load, face_of, cloud.size() * std::size_t(d));
  return load;
}

std::vector<double> trace_forces(const Scene& s, const std::vector<BoundarySpec>& boundary, const BoundaryTrace& trace,
                                 const std::vector<FacetGroup>& groups, std::size_t particles) {
  std::vector<double> force(particles * s.dim, 0.0);
  if (trace.empty()) return force;  // a local part with no facet: no traction reaches it
  const BoundaryData data{&trace.facets(), &groups, &trace};
  for (const auto& b : boundary) {
    if (!b.traction && !b.pressure) continue;
    if (b.region.is_group()) {
      // (A rank's share of a group may be empty: the whole body's loading found it.)
      const FacetGroup* group = find_group(groups, b.region.group);
      if (!group) throw std::logic_error("trace_forces: " + b.where + ": no group '" + b.region.group + "'");
      const double zero[3] = {0, 0, 0};
      add_group_traction(*group, b.traction ? b.traction->data() : zero, b.pressure.value_or(0.0), data, force);
      continue;
    }
    const auto t = side_load(b.region.side, b.traction, b.pressure.value_or(0.0), s.dim);
    add_side_traction(b.region.side, {}, t.data(), PointCloud{}, &trace, force);
  }
  return force;
}

void couple_to_faces(Loading& load, const FaceOf& face_of, const BoxGeometry& box, const PointCloud& cloud,
                     const NonlocalOperator& G, const BoundaryData& data) {
  const int d = cloud.dim;
  const BoundaryTrace* trace = data.trace && !data.trace->empty() ? data.trace : nullptr;
  std::map<std::pair<std::int64_t, int>, std::size_t> facet_of;  // (particle, side code) -> facet
  if (trace)
    for (std::size_t k = 0; k < trace->facets().size(); ++k)
      facet_of[{trace->facets().particle[k], trace->facets().side[k]}] = k;
  load.couplings.assign(1, 0);
  for (std::size_t k = 0; k < load.fixed.size(); ++k) {
    const auto it = face_of.find(load.fixed[k]);
    double self = 1.0;
    if (it != face_of.end()) {
      const std::size_t i = load.fixed[k] / d, a = load.fixed[k] % d;
      const int axis = it->second.side.axis;
      std::int64_t facet = it->second.facet;
      if (facet < 0 && trace) {
        const auto found = facet_of.find({static_cast<std::int64_t>(i), 2 * axis + (it->second.side.at_max ? 1 : 0)});
        if (found != facet_of.end()) facet = static_cast<std::int64_t>(found->second);
      }
      if (facet >= 0 && trace) {
        for (std::size_t e = trace->row_begin(facet); e < trace->row_end(facet); ++e) {
          if (trace->col(e) == static_cast<ParticleId>(i)) {
            self = trace->coef(e);
            continue;
          }
          load.coupled.push_back(static_cast<std::int64_t>(trace->col(e)) * d + a);
          load.coef.push_back(trace->coef(e));
        }
      } else {
        double r[3] = {0, 0, 0};
        if (facet >= 0)
          for (int b = 0; b < d; ++b) r[b] = data.facets->centroid[facet * d + b] - cloud.x[i * d + b];
        else
          r[axis] = (it->second.side.at_max ? box.max[axis] : box.min[axis]) - cloud.x[i * d + axis];
        G.visit_row(i, [&](ParticleId j, const double* g) {
          if (static_cast<std::size_t>(j) == i) return;  // the diagonal: self
          double c = 0.0;
          for (int b = 0; b < d; ++b) c += g[b] * r[b];
          load.coupled.push_back(static_cast<std::int64_t>(j) * d + a);
          load.coef.push_back(c);
          self -= c;
        });
      }
    }
    load.scale.push_back(1.0 / self);
    load.couplings.push_back(static_cast<Offset>(load.coupled.size()));
  }
  load.index_couplings();
}

}  // namespace perinom::detail

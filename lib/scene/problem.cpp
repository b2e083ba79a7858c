#include "perinom/scene/problem.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "perinom/core/error.hpp"
#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/geometry/mesh_body.hpp"
#include "perinom/geometry/point_file.hpp"
#include "perinom/neighbors/search.hpp"

namespace perinom {
namespace {

/// Where each face-located constraint acts: a facet (facet >= 0: its centroid, a group's
/// facet or, with a trace, the facet of the particle's lattice cell on that side), or the
/// face of a box side (axis -1: on the particle).
struct FaceRef {
  Side side;
  std::int64_t facet = -1;
};
using FaceOf = std::map<std::int64_t, FaceRef>;

/// The body's boundary as the loading sees it: the facets (the trace's when there is one)
/// and their named groups.
struct BoundaryData {
  const BoundaryFacets* facets = nullptr;
  const std::vector<FacetGroup>* groups = nullptr;
  const BoundaryTrace* trace = nullptr;
};

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

Loading make_loading(const Scene& s, const std::vector<BoundarySpec>& boundary, const PointCloud& cloud,
                     FaceOf& face_of, const BoundaryData& data) {
  const int d = s.dim;
  Loading load;
  for (const auto& b : boundary) {
    const FacetGroup* group = b.region.is_group() ? &region_group(b, data) : nullptr;
    const auto ids = group ? group_particles(*group, *data.facets) : select(b.region, s.geometry, cloud);
    if (ids.empty()) throw InputError(b.where + ".region: selects no particle");
    // A group's face constraint acts at the largest facet the particle owns in the group.
    std::map<ParticleId, std::size_t> facet_of;
    if (group)
      for (const std::size_t k : group->facets) {
        const auto it = facet_of.find(data.facets->particle[k]);
        if (it == facet_of.end() || data.facets->area[k] > data.facets->area[it->second])
          facet_of[data.facets->particle[k]] = k;
      }
    for (int a = 0; a < d; ++a) {
      if (!b.fix[a] && !b.displacement[a]) continue;
      for (const auto i : ids) {
        const std::int64_t dof = static_cast<std::int64_t>(i) * d + a;
        load.fix(dof, b.displacement[a].value_or(0.0));
        if (b.at_face) face_of[dof] = {b.region.side, group ? static_cast<std::int64_t>(facet_of.at(i)) : -1};
        else face_of.erase(dof);
      }
    }
    if (!b.traction && !b.pressure) continue;
    if (load.force.empty()) load.force.assign(cloud.size() * d, 0.0);
    if (b.pressure && load.pressure_force.empty()) load.pressure_force.assign(cloud.size() * d, 0.0);
    if (group) {
      const double zero[3] = {0, 0, 0};
      add_group_traction(*group, b.traction ? b.traction->data() : zero, b.pressure.value_or(0.0), data, load.force);
      if (b.pressure) add_group_traction(*group, zero, *b.pressure, data, load.pressure_force);
      continue;
    }
    std::array<double, 3> t{0, 0, 0}, tp{0, 0, 0};
    const auto n = outward_normal(b.region.side);
    for (int a = 0; a < d; ++a) {
      if (b.traction) t[a] += (*b.traction)[a];
      if (b.pressure) t[a] -= *b.pressure * n[a], tp[a] = -*b.pressure * n[a];
    }
    add_side_traction(b.region.side, ids, t.data(), cloud, data.trace, load.force);
    if (!b.pressure) continue;
    add_side_traction(b.region.side, ids, tp.data(), cloud, data.trace, load.pressure_force);
  }
  return load;
}

/// Face-located constraints: u_i + (grad u)_i . r = u_bar with r from the particle to the point
/// on its face, i.e. u_i (1 - sum_j c_j) + sum_j c_j u_j = u_bar with c_j = g_ij . r. With a trace
/// (the consistent formulation) the point is the centroid of the particle's facet (on that side,
/// or in that group) and the row is the trace's own, so the constraint reacts exactly where a
/// facet load acts. Without one, a group's constraint acts at its facet's centroid and a side's
/// on the box face along the side's axis.
void couple_to_faces(Loading& load, const FaceOf& face_of, const BoxGeometry& box, const PointCloud& cloud,
                     const GradientOperator& G, const BoundaryData& data) {
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
        for (Offset m = G.offsets()[i]; m < G.offsets()[i + 1]; ++m) {
          double c = 0.0;
          for (int b = 0; b < d; ++b) c += G.weight(m)[b] * r[b];
          load.coupled.push_back(static_cast<std::int64_t>(G.cols()[m]) * d + a);
          load.coef.push_back(c);
          self -= c;
        }
      }
    }
    load.scale.push_back(1.0 / self);
    load.couplings.push_back(static_cast<Offset>(load.coupled.size()));
  }
  load.index_couplings();
}

/// The particles (and facets, and groups) of a mesh or point file; errors name the key.
Body read_body(const Scene& s) {
  const BodyFiles& f = s.body_files;
  Body body;
  try {
    if (!f.mesh.empty()) body = mesh_body(read_gmsh(f.mesh), s.dim, s.geometry.thickness);
    else body.cloud = read_point_file(f.points, s.dim);
  } catch (const InputError& e) {
    throw InputError(f.where + ": " + (f.mesh.empty() ? f.points : f.mesh) + ": " + e.what());
  }
  body.cloud.dx = s.discretization.dx;
  if (!f.facets.empty()) {
    try {
      read_facet_file(f.facets, body);
    } catch (const InputError& e) {
      throw InputError(s.source + ": geometry.facets: " + f.facets + ": " + e.what());
    }
  }
  if (f.mesh.empty()) set_mean_size(body, s.geometry.thickness);
  return body;
}

}  // namespace

BoundProbe bind_probe(const ProbeSpec& p, const PointCloud& cloud) {
  const int d = cloud.dim;
  BoundProbe b{p, {}, {}};
  if (!p.is_line) {
    double best = INFINITY;
    std::size_t arg = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      double r2 = 0.0;
      for (int a = 0; a < d; ++a) r2 += std::pow(cloud.x[i * d + a] - p.point[a], 2);
      if (r2 < best) best = r2, arg = i;
    }
    b.particles.push_back(static_cast<ParticleId>(arg));
    return b;
  }
  double len2 = 0.0;
  for (int a = 0; a < d; ++a) len2 += std::pow(p.to[a] - p.from[a], 2);
  if (!(len2 > 0.0)) throw InputError(p.where + ".line: probe '" + p.name + "' has from equal to to");
  const double half = 0.5 * *std::max_element(cloud.spacing.begin(), cloud.spacing.end());
  std::vector<std::pair<double, ParticleId>> hits;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    double t = 0.0;
    for (int a = 0; a < d; ++a) t += (cloud.x[i * d + a] - p.from[a]) * (p.to[a] - p.from[a]);
    t = std::clamp(t / len2, 0.0, 1.0);
    double r2 = 0.0;
    for (int a = 0; a < d; ++a)
      r2 += std::pow(cloud.x[i * d + a] - (p.from[a] + t * (p.to[a] - p.from[a])), 2);
    if (r2 <= half * half * (1.0 + 1e-9)) hits.emplace_back(t * std::sqrt(len2), static_cast<ParticleId>(i));
  }
  if (hits.empty()) throw InputError(p.where + ".line: probe '" + p.name + "' meets no particle");
  std::sort(hits.begin(), hits.end());
  for (const auto& h : hits) {
    b.along.push_back(h.first);
    b.particles.push_back(h.second);
  }
  return b;
}

std::string horizon_key(const Scene& s) {
  return s.discretization.horizon_neighbors > 0 ? "discretization.horizon.neighbors" : "discretization.horizon.ratio";
}

Families scene_families(const Scene& s, const PointCloud& cloud) {
  try {
    return s.discretization.horizon_neighbors > 0
               ? knn_families(cloud, s.discretization.horizon_neighbors)
               : radius_families(cloud, s.discretization.horizon_ratio * s.discretization.dx);
  } catch (const InputError& e) {
    throw InputError(s.source + ": " + horizon_key(s) + ": " + e.what());
  }
}

Problem build_problem(const Scene& s, PhaseTimer* timer) {
  if (s.thin_plate()) return build_plate_problem(s, timer);
  Problem p;
  p.scene = s;
  if (timer) timer->start("discretization");
  const std::string horizon = horizon_key(s);
  Body body;
  if (s.body_files.given()) {
    body = read_body(s);
  } else {
    try {
      body.cloud = make_lattice(s.geometry, s.discretization.dx, s.discretization.jitter, s.discretization.seed);
    } catch (const InputError& e) {
      throw InputError(s.source + ": geometry: " + e.what());
    }
  }
  p.cloud = body.cloud;
  p.groups = body.groups;
  p.mesh_elements = body.elements;
  p.mean_size = body.mean_size;
  const Families families = scene_families(s, p.cloud);
  p.bonds = families.bonds();
  for (const auto& probe : s.probes) p.probes.push_back(bind_probe(probe, p.cloud));
  if (timer) timer->start("operators");
  CorrespondenceOptions opt;
  opt.influence = s.discretization.weight;
  opt.stabilization = s.model.stabilization;
  opt.operator_order = s.model.operator_order;
  parse_stabilization_storage(s.model.stabilization_storage, opt.stabilization_storage);
  opt.weight_precision =
      s.model.weight_precision == "single" ? WeightPrecision::float32 : WeightPrecision::float64;
  parse_formulation(s.model.formulation, opt.formulation);
  opt.plasticity = s.plasticity;
  if (s.model.kinematics == "finite_rotation") opt.kinematics = Kinematics::finite_rotation;
  opt.follower_pressure = s.model.follower_pressure;
  Surface surface;
  BoundaryFacets facets;
  if (s.body_files.given()) {
    facets = body.facets;
    if (!facets.empty()) p.facet_defect = divergence_theorem_defect(facets, p.cloud);
    // A mesh's facets close it to rounding; more means elements that do not share their faces.
    if (!s.body_files.mesh.empty() && !(p.facet_defect <= 1e-9))
      throw InputError(s.body_files.where + ": the mesh's boundary facets do not close it (divergence theorem defect " +
                       std::to_string(p.facet_defect) + "); is the mesh conforming?");
  } else if (opt.formulation == Formulation::consistent) {
    facets = lattice_facets(s.geometry, p.cloud);
  }
  if (opt.formulation != Formulation::classical && opt.formulation != Formulation::consistent) {
    // E: within 2 delta of the surface (THEORY sec. 5); the strong form makes E everything.
    const double delta = *std::max_element(families.support.begin(), families.support.end());
    surface = find_surface(s.geometry, p.cloud,
                           opt.formulation == Formulation::strong ? INFINITY : 2.0 * delta);
  }
  if (opt.formulation != Formulation::consistent) facets = BoundaryFacets{};
  try {
    p.model = std::make_unique<CorrespondenceModel>(p.cloud, families, s.material, opt, std::move(surface),
                                                    std::move(facets));
  } catch (const InputError& e) {
    throw InputError(s.source + ": " + horizon + ": " + e.what());
  }
  // The loads see the trace's facets (the consistent formulation) or the body's own.
  BoundaryData data{p.model->trace().empty() ? &body.facets : &p.model->trace().facets(), &p.groups, &p.model->trace()};
  FaceOf face_of;
  p.loading = make_loading(s, s.boundary, p.cloud, face_of, data);
  std::vector<FaceOf> stage_faces;
  if (s.load_path() && s.stages.empty()) {
    p.stages.push_back({"load", s.solver.load_steps, p.loading});
    stage_faces.push_back(face_of);
  }
  for (const auto& st : s.stages) {
    std::vector<BoundarySpec> boundary = s.boundary;
    boundary.insert(boundary.end(), st.boundary.begin(), st.boundary.end());
    stage_faces.emplace_back();
    p.stages.push_back({st.name, st.steps, make_loading(s, boundary, p.cloud, stage_faces.back(), data)});
  }
  if (!face_of.empty()) couple_to_faces(p.loading, face_of, s.geometry, p.cloud, p.model->G(), data);
  // The seed's collocation formulations keep collocated constraints (loading.hpp).
  const bool collocated = opt.formulation == Formulation::improved || opt.formulation == Formulation::strong;
  p.loading.collocated = collocated;
  for (auto& stage : p.stages) stage.loading.collocated = collocated;
  for (std::size_t k = 0; k < p.stages.size(); ++k)
    if (!stage_faces[k].empty()) couple_to_faces(p.stages[k].loading, stage_faces[k], s.geometry, p.cloud, p.model->G(), data);
  if (timer) timer->stop();
  return p;
}

namespace {
int axis_of(char c) { return c == 'x' ? 0 : c == 'y' ? 1 : 2; }
}  // namespace

double mean_stress(const double* sigma3) { return (sigma3[0] + sigma3[4] + sigma3[8]) / 3.0; }

double equivalent_strain(const double* H, int d) {
  double eps[9] = {};
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) eps[a * 3 + b] = 0.5 * (H[a * d + b] + H[b * d + a]);
  const double tr = (eps[0] + eps[4] + eps[8]) / 3.0;
  double ee = 0.0;
  for (int k = 0; k < 9; ++k) {
    const double e = eps[k] - (k % 4 == 0 ? tr : 0.0);
    ee += e * e;
  }
  return std::sqrt(2.0 / 3.0 * ee);
}

double probe_value(const ProbeSpec& spec, std::size_t i, const ProbeFields& f) {
  const int d = f.cloud.dim;
  if (spec.field == "displacement") return f.u[i * d + axis_of(spec.component[0])];
  if (spec.field == "stress")
    return f.sigma[i * 9 + axis_of(spec.component[0]) * 3 + axis_of(spec.component[1])];
  if (spec.field == "mean_stress") return mean_stress(f.sigma.data() + i * 9);
  if (spec.field == "equivalent_strain") return equivalent_strain(f.H.data() + i * d * d, d);
  if (spec.field == "eq_plastic_strain") return f.plastic ? f.plastic->committed()[i].law.xi : 0.0;
  return von_mises(f.sigma.data() + i * 9);
}

double point_probe_value(const BoundProbe& probe, const ProbeFields& f) {
  const std::size_t i = probe.particles.at(0);
  double v = probe_value(probe.spec, i, f);
  if (!probe.spec.reconstruct) return v;
  const int d = f.cloud.dim, a = axis_of(probe.spec.component[0]);
  for (int b = 0; b < d; ++b) v += f.H[(i * d + a) * d + b] * (probe.spec.point[b] - f.cloud.x[i * d + b]);
  return v;
}

}  // namespace perinom

#include "perinom/scene/problem.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <stdexcept>

#include "perinom/core/error.hpp"
#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/neighbors/search.hpp"

namespace perinom {
namespace {

/// The side whose face carries each face-located constraint (axis -1: on the particle).
using FaceOf = std::map<std::int64_t, Side>;

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

Loading make_loading(const Scene& s, const std::vector<BoundarySpec>& boundary,
                     const PointCloud& cloud, FaceOf& face_of, const BoundaryTrace* trace) {
  const int d = s.dim;
  Loading load;
  for (const auto& b : boundary) {
    const auto ids = select(b.region, s.geometry, cloud);
    if (ids.empty()) throw InputError(b.where + ".region: selects no particle");
    const bool constrains = std::any_of(b.fix.begin(), b.fix.begin() + d, [](bool f) { return f; }) ||
                            std::any_of(b.displacement.begin(), b.displacement.begin() + d,
                                        [](const std::optional<double>& v) { return v.has_value(); });
    const int support = constrains ? load.add_support(b.key) : -1;
    for (int a = 0; a < d; ++a) {
      if (!b.fix[a] && !b.displacement[a]) continue;
      for (const auto i : ids) {
        const std::int64_t dof = static_cast<std::int64_t>(i) * d + a;
        load.fix(dof, b.displacement[a].value_or(0.0), support);
        if (b.at_face) face_of[dof] = b.region.side;
        else face_of.erase(dof);
      }
    }
    if (!b.traction && !b.pressure) continue;
    std::array<double, 3> t{0, 0, 0}, tp{0, 0, 0};
    const auto n = outward_normal(b.region.side);
    for (int a = 0; a < d; ++a) {
      if (b.traction) t[a] += (*b.traction)[a];
      if (b.pressure) t[a] -= *b.pressure * n[a], tp[a] = -*b.pressure * n[a];
    }
    if (load.force.empty()) load.force.assign(cloud.size() * d, 0.0);
    add_side_traction(b.region.side, ids, t.data(), cloud, trace, load.force);
    if (!b.pressure) continue;
    if (load.pressure_force.empty()) load.pressure_force.assign(cloud.size() * d, 0.0);
    add_side_traction(b.region.side, ids, tp.data(), cloud, trace, load.pressure_force);
  }
  return load;
}

/// Face-located constraints: u_i + (grad u)_i . r = u_bar with r from the particle to its
/// face, i.e. u_i (1 - sum_j c_j) + sum_j c_j u_j = u_bar with c_j = g_ij . r. With a trace (the
/// consistent formulation) the point is the centroid of the particle's facet on that face and
/// the row is the trace's own, so the constraint reacts exactly where a facet load acts.
void couple_to_faces(Loading& load, const FaceOf& face_of, const BoxGeometry& box,
                     const PointCloud& cloud, const GradientOperator& G, const BoundaryTrace& trace) {
  const int d = cloud.dim;
  std::map<std::pair<std::int64_t, int>, std::size_t> facet_of;  // (particle, side code) -> facet
  for (std::size_t k = 0; k < trace.facets().size(); ++k)
    facet_of[{trace.facets().particle[k], trace.facets().side[k]}] = k;
  load.couplings.assign(1, 0);
  for (std::size_t k = 0; k < load.fixed.size(); ++k) {
    const auto it = face_of.find(load.fixed[k]);
    double self = 1.0;
    if (it != face_of.end()) {
      const std::size_t i = load.fixed[k] / d, a = load.fixed[k] % d;
      const int axis = it->second.axis;
      const auto facet = facet_of.find({static_cast<std::int64_t>(i), 2 * axis + (it->second.at_max ? 1 : 0)});
      if (facet != facet_of.end()) {
        for (std::size_t e = trace.row_begin(facet->second); e < trace.row_end(facet->second); ++e) {
          if (trace.col(e) == static_cast<ParticleId>(i)) {
            self = trace.coef(e);
            continue;
          }
          load.coupled.push_back(static_cast<std::int64_t>(trace.col(e)) * d + a);
          load.coef.push_back(trace.coef(e));
        }
      } else {
        const double r = (it->second.at_max ? box.max[axis] : box.min[axis]) - cloud.x[i * d + axis];
        for (Offset m = G.offsets()[i]; m < G.offsets()[i + 1]; ++m) {
          const double c = G.weight(m)[axis] * r;
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

/// The relative tolerance of the balance constraints: rigid_body asks of the loads: far above
/// rounding in the sums, far below any load a user means to apply.
constexpr double kBalanceTolerance = 1e-8;

/// constraints: rigid_body. Refuses loads that are not balanced (every stage's loads at its
/// end), then pins the body in every loading.
void pin_rigid_body(Problem& p) {
  const Scene& s = p.scene;
  std::vector<Loading*> loadings = {&p.loading};
  for (auto& st : p.stages) loadings.push_back(&st.loading);
  const int d = s.dim;
  for (std::size_t k = 0; k < loadings.size(); ++k) {
    const LoadResultant r = load_resultant(p.cloud, loadings[k]->force);
    if (r.balanced(kBalanceTolerance)) continue;
    auto list = [](const double* v, int n) {
      std::string out = n > 1 ? "(" : "";
      char buf[32];
      for (int a = 0; a < n; ++a) {
        std::snprintf(buf, sizeof buf, "%s%.6g", a ? ", " : "", v[a]);
        out += buf;
      }
      return out + (n > 1 ? ")" : "");
    };
    std::string text = "the external loads";
    if (k > 0) text += " of stage '" + p.stages[k - 1].name + "'";
    text += " are not balanced: resultant force " + list(r.force.data(), d) + " N, moment " +
            list(r.moment.data(), d == 2 ? 1 : 3) + " N m about the centroid, against " +
            list(&r.force_scale, 1) + " N of nodal loads (rigid_body needs a body in equilibrium under its loads alone)";
    // Layer loads act at the particles: on a jittered cloud their moments need not cancel.
    if (p.model->trace().empty() && s.discretization.jitter > 0.0)
      text += "; this formulation applies tractions at the jittered particles, whose moments need not cancel: "
              "the consistent formulation applies them at the faces";
    throw InputError(s.source + ": constraints: " + text);
  }
  try {
    p.pins = rigid_body_pins(p.cloud);
  } catch (const InputError& e) {
    throw InputError(s.source + ": constraints: rigid_body: " + e.what());
  }
  for (Loading* load : loadings) {
    const int support = load->add_support("rigid_body");
    for (const auto& pin : p.pins)
      for (const int c : pin.components) load->fix(static_cast<std::int64_t>(pin.particle) * d + c, 0.0, support);
  }
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
  try {
    p.cloud = make_lattice(s.geometry, s.discretization.dx, s.discretization.jitter, s.discretization.seed);
  } catch (const InputError& e) {
    throw InputError(s.source + ": geometry: " + e.what());
  }
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
  if (opt.formulation == Formulation::consistent) {
    facets = lattice_facets(s.geometry, p.cloud);
  } else if (opt.formulation != Formulation::classical) {
    // E: within 2 delta of the surface (THEORY sec. 5); the strong form makes E everything.
    const double delta = *std::max_element(families.support.begin(), families.support.end());
    surface = find_surface(s.geometry, p.cloud,
                           opt.formulation == Formulation::strong ? INFINITY : 2.0 * delta);
  }
  try {
    p.model = std::make_unique<CorrespondenceModel>(p.cloud, families, s.material, opt, std::move(surface),
                                                    std::move(facets));
  } catch (const InputError& e) {
    throw InputError(s.source + ": " + horizon + ": " + e.what());
  }
  const BoundaryTrace* trace = &p.model->trace();
  FaceOf face_of;
  p.loading = make_loading(s, s.boundary, p.cloud, face_of, trace);
  std::vector<FaceOf> stage_faces;
  if (s.load_path() && s.stages.empty()) {
    p.stages.push_back({"load", s.solver.load_steps, p.loading});
    stage_faces.push_back(face_of);
  }
  for (const auto& st : s.stages) {
    std::vector<BoundarySpec> boundary = s.boundary;
    boundary.insert(boundary.end(), st.boundary.begin(), st.boundary.end());
    stage_faces.emplace_back();
    p.stages.push_back({st.name, st.steps, make_loading(s, boundary, p.cloud, stage_faces.back(), trace)});
  }
  if (s.constraints == "rigid_body") pin_rigid_body(p);
  if (!face_of.empty()) couple_to_faces(p.loading, face_of, s.geometry, p.cloud, p.model->G(), *trace);
  // The seed's collocation formulations keep collocated constraints (loading.hpp).
  const bool collocated = opt.formulation == Formulation::improved || opt.formulation == Formulation::strong;
  p.loading.collocated = collocated;
  for (auto& stage : p.stages) stage.loading.collocated = collocated;
  for (std::size_t k = 0; k < p.stages.size(); ++k)
    if (!stage_faces[k].empty()) couple_to_faces(p.stages[k].loading, stage_faces[k], s.geometry, p.cloud, p.model->G(), *trace);
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

bool stress_field(const std::string& field) {
  return field == "stress" || field == "von_mises" || field == "mean_stress";
}

std::vector<double> stress_gradient(const CorrespondenceModel& model, const std::vector<double>& sigma) {
  std::vector<double> out(sigma.size() * model.G().dim());
  model.G().apply(sigma.data(), 9, out.data());
  return out;
}

void reconstruct_stress(const std::vector<double>& sigma, const std::vector<double>& grad_sigma,
                        const PointCloud& cloud, std::size_t i, const double* y, double* out) {
  const int d = cloud.dim;
  for (int c = 0; c < 9; ++c) {
    out[c] = sigma[i * 9 + c];
    for (int b = 0; b < d; ++b) out[c] += grad_sigma[(i * 9 + c) * d + b] * (y[b] - cloud.x[i * d + b]);
  }
}

double stress_probe_value(const ProbeSpec& spec, const double* sigma3) {
  if (spec.field == "stress") return sigma3[axis_of(spec.component[0]) * 3 + axis_of(spec.component[1])];
  if (spec.field == "mean_stress") return mean_stress(sigma3);
  return von_mises(sigma3);
}

double probe_value(const ProbeSpec& spec, std::size_t i, const ProbeFields& f) {
  const int d = f.cloud.dim;
  if (spec.field == "displacement") return f.u[i * d + axis_of(spec.component[0])];
  if (stress_field(spec.field)) return stress_probe_value(spec, f.sigma.data() + i * 9);
  if (spec.field == "equivalent_strain") return equivalent_strain(f.H.data() + i * d * d, d);
  if (spec.field == "eq_plastic_strain") return f.plastic ? f.plastic->committed()[i].law.xi : 0.0;
  throw std::logic_error("probe_value: unknown field " + spec.field);
}

double point_probe_value(const BoundProbe& probe, const ProbeFields& f) {
  const std::size_t i = probe.particles.at(0);
  if (probe.spec.reconstruct && stress_field(probe.spec.field)) {
    if (!f.grad_sigma) throw std::logic_error("point_probe_value: a reconstructed stress probe needs grad sigma");
    double s[9];
    reconstruct_stress(f.sigma, *f.grad_sigma, f.cloud, i, probe.spec.point.data(), s);
    return stress_probe_value(probe.spec, s);
  }
  double v = probe_value(probe.spec, i, f);
  if (!probe.spec.reconstruct) return v;
  const int d = f.cloud.dim, a = axis_of(probe.spec.component[0]);
  for (int b = 0; b < d; ++b) v += f.H[(i * d + a) * d + b] * (probe.spec.point[b] - f.cloud.x[i * d + b]);
  return v;
}

}  // namespace perinom

#include "perinom/scene/problem.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numeric>
#include <stdexcept>

#include "perinom/core/error.hpp"
#include "perinom/fracture/critical_stretch.hpp"
#include "perinom/fracture/pieces.hpp"
#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/geometry/mesh_body.hpp"
#include "perinom/geometry/point_file.hpp"
#include "perinom/geometry/region.hpp"
#include "perinom/models/cohesive_bonds.hpp"
#include "perinom/neighbors/search.hpp"
#include "scene_loading.hpp"

namespace perinom {
namespace {

namespace fs = std::filesystem;

using detail::BoundaryData;
using detail::couple_to_faces;
using detail::FaceOf;
using detail::make_loading;

/// A mesh's or point file's body against the scene's spacing: a dx more than twice the body's
/// largest extent is refused, as a lattice's is (a units slip gave a horizon of 1.5 m on a
/// 20 mm cylinder, every particle bonded to every other, and exit 0); and no two points of a
/// point file coincide (a repeated line ran, 6% off, or met a singular shape tensor whose
/// message blamed the horizon).
void check_body_size(const Body& body, const Scene& s) {
  const PointCloud& c = body.cloud;
  double extent = 0.0;
  for (int a = 0; a < c.dim; ++a) {
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = 0; i < c.size(); ++i) lo = std::min(lo, c.x[i * c.dim + a]), hi = std::max(hi, c.x[i * c.dim + a]);
    extent = std::max(extent, hi - lo);
  }
  if (s.discretization.dx > 2.0 * std::max(extent, body.mean_size)) {
    char text[320];
    std::snprintf(text, sizeof text,
                  ": discretization.dx: %g m is more than twice the body's largest extent (%g m; its particles' mean "
                  "size is %g m): the horizon would hold the whole body; dx is the horizon's length scale, "
                  "about the elements' size",
                  s.discretization.dx, extent, body.mean_size);
    throw InputError(s.source + text);
  }
  const double delta = s.discretization.horizon_ratio * s.discretization.dx;
  if (s.discretization.horizon_ratio > 0.0 && delta > 2.0 * std::max(extent, body.mean_size)) {
    char text[320];
    std::snprintf(text, sizeof text,
                  ": discretization.horizon.ratio: gives a horizon (%g m) more than twice the body's largest extent "
                  "(%g m): every particle would bond with every other",
                  delta, extent);
    throw InputError(s.source + text);
  }
  if (!s.body_files.mesh.empty() || c.size() < 2) return;
  const Families nearest = knn_families(c, 1);
  for (std::size_t i = 0; i < c.size(); ++i) {
    const std::size_t j = nearest.neighbors[nearest.begin(i)];
    if (nearest.support[i] > 1e-6 * body.mean_size) continue;
    char text[320];
    std::snprintf(text, sizeof text,
                  ": particles %zu and %zu (0-based, the header not counted) are %g m apart, a millionth of the "
                  "mean spacing %g m or less: the same point twice",
                  std::min(i, j), std::max(i, j), nearest.support[i], body.mean_size);
    throw InputError(s.body_files.where + ": " + s.body_files.points + text);
  }
}

/// The particles (and facets, and groups) of a mesh or point file; errors name the key.
Body read_body(const Scene& s) {
  const BodyFiles& f = s.body_files;
  // A folder opens as a stream and reads as an empty file: said as what it is.
  for (const auto& [file, where] : {std::pair{f.mesh, f.where}, {f.points, f.where}, {f.facets, f.facets_where}})
    if (!file.empty() && fs::is_directory(file)) throw InputError(where + ": " + file + " is a folder, not a file");
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
      read_facet_file(f.facets, body, s.geometry.thickness);
    } catch (const InputError& e) {
      throw InputError(f.facets_where + ": " + f.facets + ": " + e.what());
    }
  }
  if (f.mesh.empty()) set_mean_size(body, s.geometry.thickness);
  check_body_size(body, s);
  return body;
}

/// The relative tolerance of the balance constraints: rigid_body asks of the loads: far above
/// rounding in the sums, far below any load a user means to apply.
constexpr double kBalanceTolerance = 1e-8;

}  // namespace

void require_balanced_loads(const Problem& p, const std::vector<LoadResultant>& resultants, bool layer_loads) {
  const Scene& s = p.scene;
  const int d = s.dim;
  for (std::size_t k = 0; k < resultants.size(); ++k) {
    const LoadResultant& r = resultants[k];
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
    // Layer loads act at the particles, half a spacing inside the faces (jittered: where they
    // are): their moments need not cancel, even where the tractions' do (a pure shear on a
    // 2:1 plate: tau dx (L - h)). Without jitter the hint was left out, and the message
    // blamed balanced loads.
    if (layer_loads)
      text += "; this formulation applies tractions at the outer layer's particles (half a spacing inside the faces"
              + std::string(s.discretization.jitter > 0.0 ? ", jittered" : "") +
              "), whose moments need not cancel where the tractions' do: the consistent formulation applies them at "
              "the faces";
    throw InputError(s.source + ": constraints: " + text);
  }
}

namespace {

/// constraints: rigid_body. Refuses loads that are not balanced (every stage's loads at its
/// end) when `check` (a distributed consistent run checks its ranks' trace loads instead:
/// require_balanced_loads), then pins the body in every loading. `layer_loads`: the
/// tractions act at the particles (no trace), for the message.
void pin_rigid_body(Problem& p, bool layer_loads, bool check = true) {
  const Scene& s = p.scene;
  const int d = s.dim;
  std::vector<Loading*> loadings = {&p.loading};
  for (auto& st : p.stages) loadings.push_back(&st.loading);
  if (check) {
    std::vector<LoadResultant> resultants;
    for (const Loading* load : loadings) resultants.push_back(load_resultant(p.cloud, load->force));
    require_balanced_loads(p, resultants, layer_loads);
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

/// damage.G_c: s_c by the bond-based calibration (critical_stretch.hpp) at the median family
/// radius (the interior's horizon: k-nearest families grow at the surface).
void derive_critical_stretch(DamageSpec& d, const Scene& s, const Families& families) {
  std::vector<double> r = families.support;
  std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
  d.G_c_delta = r[r.size() / 2];
  d.s_c = critical_stretch(bond_calibration(s.material, s.discretization.weight, d.G_c_delta, s.geometry.thickness), d.G_c);
}

/// damage.fracture_energy: G_f must leave the longest bond a softening branch.
void check_fracture_energy(const DamageSpec& d, const Scene& s, const Families& families) {
  const double longest = *std::max_element(families.support.begin(), families.support.end());
  const double least = least_fracture_energy(s.dim, {d.f_t, d.fracture_energy, s.material.E}, longest);
  if (d.fracture_energy > least) return;
  char text[200];
  std::snprintf(text, sizeof text, "%g J/m^2 is below %g J/m^2, the elastic rise to f_t of a bond of the horizon's "
                "length; raise it or use the plain stress criterion", d.fracture_energy, least);
  throw InputError(s.source + ": damage.fracture_energy: " + text);
}

}  // namespace

namespace {
/// The box a lattice body fills (none for a body from files: it has no box).
const BoxGeometry* lattice_box(const Scene& s) { return s.body_files.given() ? nullptr : &s.geometry; }
}  // namespace

std::string horizon_key(const Scene& s) {
  return s.discretization.horizon_neighbors > 0 ? "discretization.horizon.neighbors" : "discretization.horizon.ratio";
}

std::string horizon_error(const Scene& s, const PointCloud& cloud, const std::string& what) {
  std::string text = s.source + ": " + horizon_key(s) + ": " + what;
  const double dx = s.discretization.dx;
  if (s.body_files.given() || s.discretization.horizon_neighbors > 0 || cloud.spacing.empty()) return text;
  const double widest = *std::max_element(cloud.spacing.begin(), cloud.spacing.end());
  if (!(widest > dx * (1.0 + 1e-9))) return text;
  char hint[400];
  std::snprintf(hint, sizeof hint,
                "; the lattice's spacing is %g m (the box's sides in whole cells), more than dx = %g m, so delta = "
                "ratio x dx = %g m spans %.4g of its spacings, not %g: a dx that divides the box's sides, or a larger "
                "ratio",
                widest, dx, s.discretization.horizon_ratio * dx, s.discretization.horizon_ratio * dx / widest,
                s.discretization.horizon_ratio);
  return text + hint;
}

Families scene_families(const Scene& s, const PointCloud& cloud) {
  try {
    return s.discretization.horizon_neighbors > 0
               ? knn_families(cloud, s.discretization.horizon_neighbors)
               : radius_families(cloud, s.discretization.horizon_ratio * s.discretization.dx);
  } catch (const InputError& e) {
    throw InputError(horizon_error(s, cloud, e.what()));
  }
}

namespace {

/// The scene's body (a mesh, a point file or a lattice) into p's cloud and groups.
Body scene_body(const Scene& s, Problem& p) {
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
  if (s.damage)  // checked here, before any solve (the breaking is set up when the solve starts)
    for (std::size_t k = 0; k < s.damage->no_fail.size(); ++k)
      detail::select_region(s.damage->no_fail[k], s, p.cloud, s.damage->no_fail_where[k]);
  return body;
}

}  // namespace

CorrespondenceOptions correspondence_options(const Scene& s) {
  CorrespondenceOptions opt;
  opt.influence = s.discretization.weight;
  opt.stabilization = s.model.stabilization;
  opt.operator_order = s.model.operator_order;
  parse_stabilization_storage(s.model.stabilization_storage, opt.stabilization_storage);
  opt.weight_precision =
      s.model.weight_precision == "single" ? WeightPrecision::float32 : WeightPrecision::float64;
  parse_formulation(s.model.formulation, opt.formulation);
  opt.plasticity = s.plasticity;
  opt.secant_stabilization = s.model.stabilization_scale == "secant";
  if (s.model.kinematics == "finite_rotation") opt.kinematics = Kinematics::finite_rotation;
  opt.follower_pressure = s.model.follower_pressure;
  opt.fracture_fields = s.damage.has_value() || !s.precracks.empty();
  return opt;
}

namespace {

/// The facets the loads and the model see: a body file's own (checked to close the body), a
/// lattice's under the consistent formulation, else none. Sets p.facet_defect.
BoundaryFacets body_facets(const Scene& s, const Body& body, Problem& p) {
  const bool consistent = s.model.formulation == "consistent";
  if (!s.body_files.given()) return consistent ? lattice_facets(s.geometry, p.cloud) : BoundaryFacets{};
  if (!body.facets.empty()) p.facet_defect = divergence_theorem_defect(body.facets, p.cloud);
  // A mesh's facets close it to rounding; more means elements that do not share their faces.
  if (!s.body_files.mesh.empty() && !(p.facet_defect <= 1e-9))
    throw InputError(s.body_files.where + ": the mesh's boundary facets do not close it (divergence theorem defect " +
                     std::to_string(p.facet_defect) + "); is the mesh conforming?");
  // The consistent formulation's boundary measure needs facets that close the body; an open
  // facet file would be projected silently and the patch test lost with exit 0.
  if (consistent && !body.facets.empty() && !(p.facet_defect <= 1e-9))
    throw InputError(s.body_files.where + ": geometry.facets: the facets do not close the body the volumes fill "
                     "(divergence theorem defect " + std::to_string(p.facet_defect) +
                     "), which the consistent formulation needs; complete them, or use formulation classical");
  return body.facets;
}

/// p.stages of a load path, from p.loading (the scene's own items) and the scene's stages,
/// with their face-located constraints in faces (one per stage).
void add_stages(Problem& p, const BoundaryData& data, std::vector<FaceOf>& faces) {
  const Scene& s = p.scene;
  for (std::size_t k = 0; k < s.stages.size() || (k == 0 && s.load_path()); ++k) {
    faces.emplace_back();
    const std::string name = s.stages.empty() ? "load" : s.stages[k].name;
    const int steps = s.stages.empty() ? s.solver.load_steps : s.stages[k].steps;
    p.stages.push_back({name, steps, make_loading(s, stage_boundary(s, k), p.cloud, faces.back(), data)});
  }
}

}  // namespace

std::vector<BoundarySpec> stage_boundary(const Scene& s, std::size_t k) {
  std::vector<BoundarySpec> boundary = s.boundary;
  if (k < s.stages.size()) boundary.insert(boundary.end(), s.stages[k].boundary.begin(), s.stages[k].boundary.end());
  return boundary;
}

InputError rigid_body_pieces_error(const Scene& s, std::int64_t count, std::int64_t second) {
  return InputError(s.source + ": constraints: rigid_body holds one body, and this one is in " + std::to_string(count) +
                    " pieces that no bond joins (particles 0 and " + std::to_string(second) +
                    " lie in different ones): hold each piece by supports");
}

Problem build_problem_frame(const Scene& s) {
  if (s.model.type != "correspondence" || (s.model.formulation != "classical" && s.model.formulation != "consistent"))
    throw std::logic_error("build_problem_frame: a correspondence scene of the classical or consistent formulation only");
  Problem p;
  p.scene = s;
  const Body body = scene_body(s, p);
  p.facets = body_facets(s, body, p);
  for (const auto& probe : s.probes) p.probes.push_back(bind_probe(probe, p.cloud, lattice_box(s)));
  BoundaryData data{&body.facets, &p.groups, nullptr};
  FaceOf face_of;
  p.loading = make_loading(s, s.boundary, p.cloud, face_of, data);  // face-located ones uncoupled (rank_loading)
  std::vector<FaceOf> stage_faces;
  add_stages(p, data, stage_faces);
  // The pins are chosen on the whole cloud, as a serial run chooses them. The loads' balance
  // is checked here on the outer layer's loads, the classical formulation's; the consistent
  // formulation applies its tractions at the faces, and its ranks check those (a balanced
  // shear was refused here: the layer's moment tau dx (L - h)).
  if (s.constraints == "rigid_body") pin_rigid_body(p, true, s.model.formulation != "consistent");
  return p;
}

Problem build_correspondence_problem(const Scene& s, PhaseTimer* timer) {
  Problem p;
  p.scene = s;
  if (timer) timer->start("discretization");
  const Body body = scene_body(s, p);
  const Families families = scene_families(s, p.cloud);
  p.bonds = families.bonds();
  if (p.scene.damage && p.scene.damage->G_c > 0.0) derive_critical_stretch(*p.scene.damage, s, families);
  if (p.scene.damage && p.scene.damage->fracture_energy > 0.0) check_fracture_energy(*p.scene.damage, s, families);
  for (const auto& probe : s.probes) p.probes.push_back(bind_probe(probe, p.cloud, lattice_box(s)));
  if (timer) timer->start("operators");
  const CorrespondenceOptions opt = correspondence_options(s);
  Surface surface;
  BoundaryFacets facets = body_facets(s, body, p);
  p.facets = facets;
  if (opt.formulation != Formulation::classical && opt.formulation != Formulation::consistent) {
    // E: within 2 delta of the surface (THEORY sec. 5); the strong form makes E everything.
    const double delta = *std::max_element(families.support.begin(), families.support.end());
    surface = find_surface(s.geometry, p.cloud,
                           opt.formulation == Formulation::strong ? INFINITY : 2.0 * delta);
  }
  if (opt.formulation != Formulation::consistent) facets = BoundaryFacets{};
  std::unique_ptr<CorrespondenceModel> model;
  try {
    model = std::make_unique<CorrespondenceModel>(p.cloud, families, s.material, opt, std::move(surface),
                                                  std::move(facets));
  } catch (const InputError& e) {
    throw InputError(horizon_error(s, p.cloud, e.what()));
  }
  // Precracks cut their bonds as a broken bond is cut (the reader allows them with the
  // classical formulation only).
  if (!s.precracks.empty()) {
    // Each crack on its own: one that cuts nothing was ignored when another cut bonds.
    for (std::size_t k = 0; k < s.precracks.size(); ++k)
      if (bonds_crossing(p.cloud, families, {s.precracks[k]}).empty())
        throw InputError(s.source + ": precracks[" + std::to_string(k) +
                         "] cuts no bond (does it cross the body between particles?)");
    model->cut_bonds(bonds_crossing(p.cloud, families, s.precracks));
  }
  // The loads see the trace's facets (the consistent formulation) or the body's own.
  BoundaryData data{model->trace().empty() ? &body.facets : &model->trace().facets(), &p.groups, &model->trace()};
  FaceOf face_of;
  p.loading = make_loading(s, s.boundary, p.cloud, face_of, data);
  std::vector<FaceOf> stage_faces;
  add_stages(p, data, stage_faces);
  if (s.constraints == "rigid_body") {
    // Its pins hold one body: on a body in pieces they held one piece twice over and left
    // the other free (Newton then blamed a missing boundary condition on the user).
    const Pieces pieces = body_pieces(model->G().graph(), {});
    if (pieces.count > 1)
      throw rigid_body_pieces_error(s, pieces.count,
                                    std::find(pieces.piece.begin(), pieces.piece.end(), 1) - pieces.piece.begin());
    pin_rigid_body(p, model->trace().empty());
  }
  if (!face_of.empty()) couple_to_faces(p.loading, face_of, s.geometry, p.cloud, model->G(), data);
  // The seed's collocation formulations keep collocated constraints (loading.hpp).
  const bool collocated = opt.formulation == Formulation::improved || opt.formulation == Formulation::strong;
  p.loading.collocated = collocated;
  for (auto& stage : p.stages) stage.loading.collocated = collocated;
  for (std::size_t k = 0; k < p.stages.size(); ++k)
    if (!stage_faces[k].empty()) couple_to_faces(p.stages[k].loading, stage_faces[k], s.geometry, p.cloud, model->G(), data);
  p.model = std::move(model);
  if (timer) timer->stop();
  return p;
}

}  // namespace perinom

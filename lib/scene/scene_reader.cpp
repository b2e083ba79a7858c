// Reads a scene file into a Scene, strictly: unknown keys, wrong types, missing keys and
// values out of range all end in an InputError that names the key and its line.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "perinom/core/error.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/scene/registry.hpp"
#include "perinom/scene/scene.hpp"
#include "perinom/solvers/petsc.hpp"
#include "plate_keys.hpp"
#include "scene_sections.hpp"
#include "yaml_fields.hpp"

namespace perinom {
namespace {

/// The longest scene name: NAME_000000_R.pvtu.tmp must fit a file name's 255 bytes.
constexpr std::size_t kLongestName = 200;

using detail::Fields;

using detail::axis_of;
using detail::read_boundary;
using detail::read_probes;
using detail::read_stages;

/// A file named by a geometry key, resolved against the scene file's folder.
std::string scene_relative(const std::string& source, const std::string& file) {
  const std::filesystem::path p(file);
  if (p.is_absolute()) return file;
  return (std::filesystem::path(source).parent_path() / p).string();
}

/// geometry.mesh, or geometry.points with geometry.facets: the body from files.
void read_body_files(Fields& f, Scene& s) {
  auto& b = s.body_files;
  const char* key = f.has("mesh") ? "mesh" : "points";
  b.where = detail::where(s.source, f.node(key)) + f.key(key);
  const std::string file = f.text(key);
  if (file.empty()) f.fail(key, "must name a file");
  (f.has("mesh") ? b.mesh : b.points) = scene_relative(s.source, file);
  if (f.has("facets")) {
    if (b.points.empty()) f.fail("facets", "belongs to geometry.points (a mesh carries its own facets)");
    const std::string facets = f.text("facets");
    if (facets.empty()) f.fail("facets", "must name a file");
    b.facets = scene_relative(s.source, facets);
    b.facets_where = detail::where(s.source, f.node("facets")) + f.key("facets");
  }
  if (f.has("holes")) f.fail("holes", std::string("cut a box; geometry.") + key + " carries its own shape");
}

void read_geometry(Fields f, Scene& s) {
  auto& g = s.geometry;
  g.dim = s.dim;
  if (int(f.has("box")) + int(f.has("mesh")) + int(f.has("points")) != 1)
    f.fail("box", "give exactly one of box (a lattice), mesh (a gmsh .msh file) or points (a CSV file)");
  g.thickness = f.number("thickness", 1.0);
  if (!(g.thickness > 0.0)) f.fail("thickness", "must be positive");
  if (!f.has("box")) {
    read_body_files(f, s);
    return f.finish();
  }
  if (f.has("facets")) f.fail("facets", "belongs to geometry.points (a box's facets are its lattice cells')");
  Fields box = f.map("box");
  const auto lo = box.vector("min", s.dim), hi = box.vector("max", s.dim);
  box.finish();
  for (int a = 0; a < s.dim; ++a)
    if (!(hi[a] > lo[a])) f.fail("box", "max must exceed min on every axis (empty geometry)");
  g.min = lo;
  g.max = hi;
  const auto holes = f.list("holes");
  for (std::size_t k = 0; k < holes.size(); ++k) {
    Fields h(holes[k], f.key("holes[" + std::to_string(k) + "]"), f.source());
    Hole hole;
    const std::string shape = h.text("shape", s.dim == 2 ? "circle" : "sphere");
    if (s.dim == 2 && shape == "circle") hole.shape = Hole::Shape::circle;
    else if (s.dim == 3 && shape == "sphere") hole.shape = Hole::Shape::sphere;
    else if (s.dim == 3 && shape == "cylinder") hole.shape = Hole::Shape::cylinder;
    else h.fail("shape", "must be circle (2-D), sphere or cylinder (3-D)");
    hole.center = h.vector("center", s.dim);
    hole.radius = h.number("radius");
    if (!(hole.radius > 0.0)) h.fail("radius", "must be positive");
    if (hole.shape == Hole::Shape::cylinder) {
      hole.axis = axis_of(h.text("axis", "z"), 3);
      if (hole.axis < 0) h.fail("axis", "must be x, y or z");
    }
    h.finish();
    g.holes.push_back(hole);
  }
  f.finish();
}

/// The lattice's cell counts in double, before any integer conversion: a spacing of 1e-300
/// gives counts no integer holds, one of 1e308 gives none at all.
void check_lattice_size(Fields& f, const Scene& s) {
  const double dx = s.discretization.dx;
  double cells = 1.0;
  for (int a = 0; a < s.dim; ++a) {
    const double along = (s.geometry.max[a] - s.geometry.min[a]) / dx;
    if (!(along >= 0.5))
      f.fail("dx", "is more than twice the box's length along " + std::string(1, "xyz"[a]) +
                       " (the lattice would hold no particle there)");
    cells *= along;
  }
  if (!(cells <= 2.0e9))
    f.fail("dx", "gives about " + std::to_string(cells).substr(0, 12) +
                     " lattice cells, more than perinom's limit of 2e9 particles");
}

void read_discretization(Fields f, Scene& s) {
  auto& d = s.discretization;
  d.dx = f.number("dx");
  if (!(d.dx > 0.0)) f.fail("dx", "must be positive");
  if (!s.body_files.given()) check_lattice_size(f, s);  // a body from files has no lattice
  Fields h = f.map("horizon");
  if (h.has("ratio") == h.has("neighbors"))
    f.fail("horizon", "give exactly one of ratio (delta = ratio * dx) or neighbors (k nearest)");
  if (h.has("ratio")) {
    d.horizon_ratio = h.number("ratio");
    if (!(d.horizon_ratio > 0.0)) h.fail("ratio", "must be positive");
    if (!std::isfinite(d.horizon_ratio * d.dx)) h.fail("ratio", "times dx is not a finite length");
    // A horizon beyond the body bonds every particle to every other (ratio 1e6 on the Kalthoff
    // plate: 10 million bonds, a gigabyte and seconds of building before any answer).
    double largest = 0.0;
    for (int a = 0; a < s.dim && !s.body_files.given(); ++a)
      largest = std::max(largest, s.geometry.max[a] - s.geometry.min[a]);
    if (largest > 0.0 && d.horizon_ratio * d.dx > 2.0 * largest)
      h.fail("ratio", "gives a horizon (ratio * dx = " + std::to_string(d.horizon_ratio * d.dx) +
                          " m) more than twice the box's largest side: every particle would bond with every other");
  } else {
    const auto k = h.small_integer("neighbors", 0);
    if (k < s.dim) h.fail("neighbors", "must be at least the dimension");
    d.horizon_neighbors = static_cast<int>(k);
  }
  h.finish();
  if (!parse_influence(f.text("weight", "inverse_square"), d.weight))
    f.fail("weight", "must be constant, inverse_distance, inverse_square or gaussian");
  d.jitter = f.number("jitter", 0.0);
  if (d.jitter < 0.0 || d.jitter >= 1.0) f.fail("jitter", "must lie in [0, 1)");
  if (d.jitter > 0.0 && s.body_files.given()) f.fail("jitter", "moves lattice particles; a mesh or point file places its own");
  d.seed = static_cast<std::uint64_t>(f.integer("seed", 1));
  f.finish();
}

/// material.type: drucker_prager: the law's constants (THEORY sec. 9), angles in degrees.
DruckerPrager read_drucker_prager(Fields& f, const LinearElastic& m) {
  DruckerPrager dp;
  dp.E = m.E;
  dp.nu = m.nu;
  const double phi = f.number("friction_angle");
  if (!(phi >= 0.0 && phi < 90.0)) f.fail("friction_angle", "must lie in [0, 90) degrees");
  dp.friction_angle = phi * M_PI / 180.0;
  dp.cohesion = f.number("cohesion");
  if (!(dp.cohesion >= 0.0)) f.fail("cohesion", "must be zero or positive (Pa)");
  dp.m0 = f.number("m0", 1.0);
  if (!(dp.m0 > 0.0 && dp.m0 <= 1.0)) f.fail("m0", "must lie in (0, 1]");
  dp.d0 = f.number("d0", 0.0);
  if (!(dp.d0 >= 0.0 && dp.d0 <= 1.0)) f.fail("d0", "must lie in [0, 1] (0: no dilatancy, 1: associated flow)");
  dp.h = f.number("h", 0.0);
  if (!(dp.h >= 0.0)) f.fail("h", "must be zero or positive (0: no hardening)");
  if (dp.cohesion == 0.0 && phi == 0.0) f.fail("cohesion", "and friction_angle are both zero: the material has no strength");
  return dp;
}

void read_material(Fields f, Scene& s) {
  auto& m = s.material;
  m.dim = s.dim;
  const std::string type = f.text("type");
  if (type != "linear_elastic" && type != "drucker_prager")
    f.fail("type", "unknown material type (known: linear_elastic, drucker_prager)");
  m.E = f.number("E");
  if (!(m.E > 0.0)) f.fail("E", "must be positive");
  m.nu = f.number("nu");
  if (!(m.nu > -1.0 && m.nu < 0.5)) f.fail("nu", "must lie in (-1, 0.5)");
  m.density = f.number("density");
  if (!(m.density > 0.0)) f.fail("density", "must be positive");
  if (s.dim == 2) {
    const std::string plane = f.text("plane", "strain");
    if (plane == "strain") m.plane = PlaneCondition::strain;
    else if (plane == "stress") m.plane = PlaneCondition::stress;
    else f.fail("plane", "must be strain or stress");
  } else if (f.has("plane")) {
    f.fail("plane", "only 2-D scenes have a plane condition");
  } else {
    f.mark("plane");  // plane: null is absent, as everywhere
  }
  if (type == "drucker_prager") {
    if (m.plane == PlaneCondition::stress) f.fail("plane", "Drucker-Prager plasticity needs plane strain");
    s.plasticity = read_drucker_prager(f, m);
  }
  f.finish();
}

/// model.type from the registry, then that model's keys.
void read_model(Fields f, Scene& s) {
  s.model.type = f.text("type", ModelSpec{}.type);
  const ModelEntry* entry = find_model(s.model.type);
  if (!entry) f.fail("type", "unknown model type (known: " + model_names() + ")");
  entry->read(f, s);
}

}  // namespace

namespace detail {

void read_correspondence_model(Fields& f, Scene& s) {
  s.model.formulation = f.text("formulation", ModelSpec{}.formulation);
  Formulation parsed;
  if (!parse_formulation(s.model.formulation, parsed))
    f.fail("formulation", "must be consistent, classical, improved or strong");
  s.model.stabilization = f.number("stabilization", ModelSpec{}.stabilization);
  if (s.model.stabilization < 0.0) f.fail("stabilization", "must be zero or positive");
  s.model.stabilization_storage = f.text("stabilization_storage", ModelSpec{}.stabilization_storage);
  StabilizationStorage storage;
  if (!parse_stabilization_storage(s.model.stabilization_storage, storage))
    f.fail("stabilization_storage", "must be auto, fused, assembled or matrix_free");
  s.model.weight_precision = f.text("weight_precision", ModelSpec{}.weight_precision);
  if (s.model.weight_precision != "double" && s.model.weight_precision != "single")
    f.fail("weight_precision", "must be double or single");
  // The consistent formulation fits second order by default: bending needs G exact for
  // quadratic fields at the surface (first order: +40% on a cantilever 4 particles thick).
  s.model.operator_order = f.small_integer("operator_order", s.model.formulation == "consistent" ? 2 : 1);
  if (s.model.operator_order != 1 && s.model.operator_order != 2) f.fail("operator_order", "must be 1 or 2");
  if (s.model.operator_order == 2 && s.model.stabilization > 0.0 && storage == StabilizationStorage::fused)
    f.fail("stabilization_storage", "with operator_order 2 the stabilization is the second-order operator energy, "
                                    "assembled or matrix_free (fused rests on the first-order fit; use auto, assembled "
                                    "or matrix_free)");
  if (s.model.formulation == "consistent" && s.model.operator_order == 1 && s.model.stabilization > 0.0 &&
      storage != StabilizationStorage::automatic && storage != StabilizationStorage::assembled)
    f.fail("stabilization_storage", "the consistent formulation with operator_order 1 stores the stabilization "
                                    "assembled (use auto or assembled)");
  s.model.stabilization_scale = f.text("stabilization_scale", ModelSpec{}.stabilization_scale);
  if (s.model.stabilization_scale != "elastic" && s.model.stabilization_scale != "secant")
    f.fail("stabilization_scale", "must be elastic or secant");
  if (s.model.stabilization_scale == "secant") {
    if (!s.plasticity) f.fail("stabilization_scale", "secant follows a drucker_prager material's plastic states");
    if (!(s.model.stabilization > 0.0)) f.fail("stabilization_scale", "secant scales a stabilization: needs model.stabilization > 0");
    if (storage != StabilizationStorage::automatic && storage != StabilizationStorage::matrix_free)
      f.fail("stabilization_scale", "secant scales each family's block of S, which only the matrix-free storage "
                                    "keeps apart (stabilization_storage auto or matrix_free)");
    if (s.model.formulation == "consistent" && s.model.operator_order == 1)
      f.fail("stabilization_scale", "secant needs a matrix-free stabilization, which the consistent formulation "
                                    "has at operator_order 2 only");
  }
  s.model.kinematics = f.text("kinematics", ModelSpec{}.kinematics);
  if (s.model.kinematics != "small_strain" && s.model.kinematics != "finite_rotation")
    f.fail("kinematics", "must be small_strain or finite_rotation");
  if (s.model.kinematics == "finite_rotation" && !s.plasticity)
    f.fail("kinematics", "finite_rotation is implemented for the drucker_prager material only");
  s.model.follower_pressure = f.boolean("follower_pressure", s.model.kinematics == "finite_rotation");
  if (s.model.follower_pressure && s.model.kinematics != "finite_rotation")
    f.fail("follower_pressure", "needs kinematics: finite_rotation (small strain reads loads in the reference configuration)");
  f.finish();
}

}  // namespace detail

namespace {

/// solver.type from the registry; the keys start from that solver's defaults.
void read_solver(Fields f, Scene& s) {
  auto& v = s.solver;
  v.type = f.text("type", s.plasticity ? "lbc" : "adr");
  const SolverEntry* entry = find_solver(v.type);
  if (!entry) f.fail("type", "must be " + solver_names_or());
  {
    const std::string type = v.type;
    v = entry->defaults;
    v.type = type;
  }
  if (v.type == "verlet" && s.plasticity)
    f.fail("type", "verlet is not available with a drucker_prager material (use lbc, adr or newton)");
  if (v.type == "verlet" && !s.stages.empty()) f.fail("type", "verlet does not run load stages (use lbc, adr or newton)");
  if (v.type == "direct" && s.plasticity)
    f.fail("type", "direct solves a linear problem in one factorization; a drucker_prager material needs lbc, adr or newton");
  if (v.type == "direct" && !s.stages.empty()) f.fail("type", "direct does not run load stages (use lbc, adr or newton)");
  if (v.type == "direct" && (s.model.formulation == "improved" || s.model.formulation == "strong"))
    f.fail("type", "direct needs a symmetric stiffness (the consistent or classical formulation); the " +
                       s.model.formulation + " formulation is not symmetric: use newton or adr");
  if (!find_model(s.model.type)->load_path_schemes && find_solver(v.type) && !find_solver(v.type)->single)
    f.fail("type", "a " + s.model.type + " is elastic: solve it by adr or newton (static) or verlet (dynamic)");
  if (!s.stages.empty() && f.has("load_steps")) f.fail("load_steps", "with stages, each stage sets its steps");
  const bool newton = v.type == "newton";
  v.tolerance = f.number("tolerance", v.tolerance);
  if (!(v.tolerance > 0.0 && v.tolerance < 1.0)) f.fail("tolerance", "must lie in (0, 1): it is relative");
  v.displacement_tolerance = f.number("displacement_tolerance", v.displacement_tolerance);
  if (!(v.displacement_tolerance > 0.0 && v.displacement_tolerance < 1.0)) f.fail("displacement_tolerance", "must lie in (0, 1): it is relative");
  v.max_iterations = f.integer("max_iterations", v.max_iterations);
  if (v.max_iterations < 1) f.fail("max_iterations", "must be at least 1");
  v.load_steps = f.small_integer("load_steps", v.load_steps);
  if (v.load_steps < 1) f.fail("load_steps", "must be at least 1");
  v.dt = f.number("dt", v.dt);
  if (v.dt < 0.0) f.fail("dt", "must be positive (or 0 for the stable step)");
  v.safety = f.number("safety", v.safety);
  if (!(v.safety > 0.0 && v.safety <= 1.0)) f.fail("safety", "must lie in (0, 1]");
  v.steps = f.integer("steps", v.steps);
  if (v.steps < 1) f.fail("steps", "must be at least 1");
  v.ramp_time = f.number("ramp_time", v.ramp_time);
  if (v.ramp_time < 0.0) f.fail("ramp_time", "must be zero or positive");
  v.history_every = f.integer("history_every", v.history_every);
  if (v.history_every < 1) f.fail("history_every", "must be at least 1");
  v.line_search = f.boolean("line_search", v.line_search);
  v.step_tolerance = f.number("step_tolerance", v.step_tolerance);
  if (!(v.step_tolerance > 0.0 && v.step_tolerance < 1.0)) f.fail("step_tolerance", "must lie in (0, 1): it is relative");
  v.linear_solver = f.text("linear_solver", v.linear_solver);
  if (v.linear_solver != "klu" && v.linear_solver != "umfpack" && v.linear_solver != "mumps" &&
      v.linear_solver != "gamg")
    f.fail("linear_solver", "must be klu, umfpack, mumps or gamg");
  v.check = f.text("check", "none");
  if (v.check != "none" && v.check != "newton") f.fail("check", "must be none or newton");
  if (v.check == "newton" && v.type != "adr" && v.type != "lbc")
    f.fail("check", "the Newton check compares static answers: it needs solver.type adr or lbc");
  // Only where a Newton solve will read it (other solvers ignore it, as other solvers' keys).
  const bool petsc = (v.linear_solver == "mumps" || v.linear_solver == "gamg") && (newton || v.check == "newton");
  if (petsc && !petsc_available())
    f.fail("linear_solver", v.linear_solver + " needs PETSc, and this perinom was built without it (install "
                            "petsc-dev and rebuild)");
  if (petsc && (s.model.formulation == "improved" || s.model.formulation == "strong"))
    f.fail("linear_solver", v.linear_solver + " solves the Galerkin-reduced system; the " + s.model.formulation +
                                " formulation collocates its constraints: use umfpack or klu");
  v.yield_tolerance = f.number("yield_tolerance", v.yield_tolerance);
  if (!(v.yield_tolerance > 0.0 && v.yield_tolerance < 1.0)) f.fail("yield_tolerance", "must lie in (0, 1): it is relative");
  v.max_rounds = f.small_integer("max_rounds", v.max_rounds);
  if (v.max_rounds < 1) f.fail("max_rounds", "must be at least 1");
  if (newton && v.max_iterations > 1000000000) f.fail("max_iterations", "is out of range");
  v.energy_check = f.boolean("energy_check", v.energy_check);
  v.energy_tolerance = f.number("energy_tolerance", v.energy_tolerance);
  if (!(v.energy_tolerance > 0.0)) f.fail("energy_tolerance", "must be positive");
  v.allow_unstable = f.boolean("allow_unstable", v.allow_unstable);
  f.finish();
}

/// constraints: rigid_body holds a free body by pins the builder chooses; supports of its own
/// would fight them, so it takes none.
void read_constraints(Fields& top, Scene& s) {
  s.constraints = top.text("constraints", "none");
  if (s.constraints != "none" && s.constraints != "rigid_body") top.fail("constraints", "must be none or rigid_body");
  if (s.constraints == "none") return;
  if (!find_model(s.model.type)->rigid_body)
    top.fail("constraints", "rigid_body does not apply to a " + s.model.type + " (its boundary holds it)");
  auto constrains = [&](const BoundarySpec& b) {
    for (int a = 0; a < s.dim; ++a)
      if (b.fix[a] || b.displacement[a] || b.velocity[a]) return true;
    return false;
  };
  std::vector<const BoundarySpec*> all;
  for (const auto& b : s.boundary) all.push_back(&b);
  for (const auto& st : s.stages)
    for (const auto& b : st.boundary) all.push_back(&b);
  for (const BoundarySpec* b : all)
    if (constrains(*b))
      top.fail("constraints", "rigid_body is for a body held by no support, but " + b->key +
                                  " fixes or prescribes displacements (remove one or the other)");
}

/// The improved and strong formulations have strong-form rows: K is not symmetric, M^-1 K
/// has negative and complex eigenvalues, and explicit dynamics grows them exponentially
/// whatever the step (issue 14; solvers/spectrum.hpp measures them). Verlet refuses them
/// unless solver.allow_unstable.
void refuse_unstable_dynamics(const YAML::Node& root, const Scene& s) {
  if (s.solver.type != "verlet" || s.solver.allow_unstable) return;
  if (s.model.formulation != "improved" && s.model.formulation != "strong") return;
  const YAML::Node model = root["model"];
  throw InputError(detail::where(s.source, model ? model["formulation"] : model) + "model.formulation: " +
                   s.model.formulation + " is non-symmetric and unstable in explicit dynamics (solver.type verlet); "
                   "use consistent or classical, or set solver.allow_unstable: true to run it anyway");
}

}  // namespace

namespace detail {

/// A body from files has no box, so only the formulations that need no box surface apply;
/// the consistent one needs facets, which a point file has only with geometry.facets.
void check_body_formulation(const YAML::Node& root, const Scene& s) {
  if (!s.body_files.given()) return;
  YAML::Node key = root;  // the line of model.formulation if given, else of the scene's first key
  if (const YAML::Node model = root["model"]; model.IsDefined() && model.IsMap() && model["formulation"].IsDefined())
    key.reset(model["formulation"]);  // reset: operator= would overwrite the root node itself
  const std::string at = detail::where(s.source, key) + "model.formulation: ";
  const std::string body = s.body_files.mesh.empty() ? "geometry.points" : "geometry.mesh";
  if (s.model.formulation == "improved" || s.model.formulation == "strong")
    throw InputError(at + s.model.formulation + " finds the surface of a box; with " + body +
                     " use consistent or classical");
  if (s.model.formulation == "consistent" && s.body_files.mesh.empty() && s.body_files.facets.empty())
    throw InputError(at + "the consistent formulation (the default) needs the boundary facets, and " + body +
                     " has none: give geometry.facets, or use formulation classical");
}

}  // namespace detail

namespace {

/// The scene text as one YAML document. A second document (a stray "---") would be
/// dropped by YAML::Load without a word, and with it every key below the separator.
YAML::Node load_one_document(const std::string& text, const std::string& source) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(source + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  detail::require_closed_quotes(text, source);
  if (documents.size() <= 1) return documents.empty() ? YAML::Node() : documents[0];
  // The separator's line: the first "---" or "..." line after some content.
  std::istringstream in(text);
  bool content = false;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const bool marker = (line.rfind("---", 0) == 0 || line.rfind("...", 0) == 0) &&
                        (line.size() == 3 || line[3] == ' ' || line[3] == '\t' || line[3] == '\r');
    if (marker && content)
      throw InputError(source + ":" + std::to_string(number) +
                       ": a second YAML document starts here ('" + line.substr(0, 3) +
                       "'); a scene is one document (remove the line)");
    const auto first = line.find_first_not_of(" \t\r");
    if (!marker && first != std::string::npos && line[first] != '#' && line[first] != '%') content = true;
  }
  throw InputError(source + ": the file holds " + std::to_string(documents.size()) +
                   " YAML documents; a scene is one document");
}

/// The scene without its `output` section (which changes what is written, not what is
/// solved), as yaml-cpp writes it.
std::string canonical_text(const YAML::Node& root) {
  YAML::Node copy = YAML::Clone(root);
  copy.remove("output");
  return YAML::Dump(copy);
}

/// A name safe as a file and folder name on every system: letters, digits, '_', '-', '.',
/// and not "." or ".." (which name folders that already exist).
bool is_file_name(const std::string& name) {
  if (name.empty() || name == "." || name == "..") return false;
  return name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") ==
         std::string::npos;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source,
                  const std::vector<std::string>& overrides) {
  YAML::Node root = load_one_document(text, source);
  if (!root.IsMap()) throw InputError(source + ": a scene is a mapping of keys to values");
  std::vector<YAML::Node> given;
  for (const auto& o : overrides) given.push_back(detail::apply_override(root, o));
  const detail::OverrideSources named(given, overrides);
  Scene s;
  s.source = source;
  s.canonical = canonical_text(root);
  Fields top(root, "", source);
  s.name = top.text("name");
  if (!is_file_name(s.name))
    top.fail("name", "must be made of letters, digits, '_', '-' and '.', and not be '.' or '..' "
                     "(it names the output folder and files)");
  // Checked before the solve: a name of 241 characters ran a whole solve, then its first
  // snapshot's file name (NAME_000000.vtu.tmp) was too long for the file system.
  if (s.name.size() > kLongestName)
    top.fail("name", "is " + std::to_string(s.name.size()) + " characters long: at most " + std::to_string(kLongestName) +
                         " (files are named after it, NAME_000000_R.pvtu.tmp, and a file name holds 255 bytes)");
  s.dim = top.small_integer("dimension", 0);
  if (s.dim != 2 && s.dim != 3) top.fail("dimension", "must be 2 or 3");
  read_geometry(top.map("geometry"), s);
  read_discretization(top.map("discretization"), s);
  read_material(top.map("material"), s);
  if (top.has("model")) read_model(top.map("model"), s);
  else top.mark("model");
  find_model(s.model.type)->check(root, s);
  s.boundary = read_boundary(top.list("boundary"), source, s);
  read_stages(top.list("stages"), source, s);
  read_constraints(top, s);
  if (top.has("solver")) read_solver(top.map("solver"), s);
  else top.mark("solver"), s.solver.type = s.plasticity ? "lbc" : "adr";
  if (top.has("output")) {
    Fields o = top.map("output");
    s.output.vtk_every = o.integer("vtk_every", 0);
    if (s.output.vtk_every < 0) o.fail("vtk_every", "must be zero or positive");
    for (const auto& n : o.list("vtk_steps")) {
      std::int64_t step = 0;
      try {
        step = n.as<std::int64_t>();
      } catch (const YAML::Exception&) {
        o.fail("vtk_steps", "must be a list of load step numbers");
      }
      if (step < 1) o.fail("vtk_steps", "load steps are counted from 1");
      s.output.vtk_steps.push_back(step);
    }
    if (!s.output.vtk_steps.empty() && !s.load_path())
      o.fail("vtk_steps", "counts load steps, and this scene has none (no stages, plasticity or solver.type lbc); "
                          "use vtk_every");
    s.output.csv = o.boolean("csv", s.output.csv);
    s.output.checkpoint_every = o.integer("checkpoint_every", 0);
    if (s.output.checkpoint_every < 0) o.fail("checkpoint_every", "must be zero or positive");
    if (s.output.checkpoint_every > 0 && s.solver.type == "newton")
      o.fail("checkpoint_every", "Newton solves are not checkpointed (KINSOL's state between load steps is not "
                                 "kept); use solver.type adr or lbc, or remove the key");
    o.finish();
  } else {
    top.mark("output");
  }
  read_probes(top.list("probes"), source, s);
  detail::read_fracture(top, s);
  top.finish();
  refuse_unstable_dynamics(root, s);
  return s;
}

Scene read_scene(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the scene file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_scene(buffer.str(), path, overrides);
}

}  // namespace perinom

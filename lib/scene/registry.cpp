// The tables of models and solvers (registry.hpp): one row each, with the keys it reads, its
// defaults and its factory.
#include "perinom/scene/registry.hpp"

#include <cstdio>
#include <optional>
#include <stdexcept>
#include <utility>

#include "perinom/scene/scene_breaking.hpp"
#include "plate_keys.hpp"
#include "scene_sections.hpp"

namespace perinom {

Problem build_correspondence_problem(const Scene& scene, PhaseTimer* timer);

namespace {

std::string text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::vector<ModelEntry> make_models() {
  const ModelSpec d;
  ModelEntry correspondence;
  correspondence.name = "correspondence";
  correspondence.keys = {
      {"formulation", d.formulation, "consistent | classical | improved | strong"},
      {"stabilization", text(d.stabilization), "C_hg"},
      {"stabilization_storage", d.stabilization_storage, "auto | fused | assembled | matrix_free"},
      {"stabilization_scale", d.stabilization_scale, "elastic | secant (drucker_prager only)"},
      {"weight_precision", d.weight_precision, "double | single"},
      {"operator_order", "", "2 with the consistent formulation, 1 otherwise"},
      {"kinematics", d.kinematics, "small_strain | finite_rotation (drucker_prager only)"},
      {"follower_pressure", "", "true with finite_rotation, false otherwise"}};
  correspondence.read = detail::read_correspondence_model;
  correspondence.check = detail::check_body_formulation;
  correspondence.build = build_correspondence_problem;
  correspondence.read_boundary = detail::read_body_boundary;
  correspondence.memory = [](const Scene& s) {
    const int d = s.dim;
    MemoryRates r;
    r.per_bond = s.model.operator_order == 2 ? (d == 2 ? 283.0 : 421.0) : (d == 2 ? 106.0 : 118.0);
    if (s.plasticity) r.per_particle = d == 2 ? 430.0 : 650.0;  // the committed and trial states
    return r;
  };
  ModelEntry plate;
  plate.name = "thin_plate";
  plate.keys = {{"stabilization", text(d.stabilization), "C_hg of the operator energy"}};
  plate.read = detail::read_plate_model;
  plate.check = detail::check_plate_scene;
  plate.build = build_plate_problem;
  plate.memory = [](const Scene&) { return MemoryRates{157.0, 0.0, true}; };
  plate.read_boundary = detail::read_plate_boundary;
  plate.probe_field = "deflection";
  plate.probe_field_only = true;
  plate.stages = false;
  plate.load_path_schemes = false;
  plate.rigid_body = false;
  return {correspondence, plate};
}

SolverEntry row(std::string name, std::vector<OptionKey> keys, const SolverSpec& defaults, bool load_path, bool single) {
  SolverEntry e;
  e.name = std::move(name), e.keys = std::move(keys), e.defaults = defaults;
  e.load_path = load_path, e.single = single;
  return e;
}

std::vector<SolverEntry> make_solvers() {
  const SolverSpec d;
  const std::vector<OptionKey> balance = {{"tolerance", text(d.tolerance), ""},
                                          {"displacement_tolerance", text(d.displacement_tolerance), ""},
                                          {"max_iterations", std::to_string(d.max_iterations), ""},
                                          {"load_steps", std::to_string(d.load_steps), ""},
                                          {"history_every", std::to_string(d.history_every), ""}};
  SolverEntry adr = row("adr", balance, d, true, true);
  adr.solve = [](Problem& p, std::vector<double>& u, const SolveHooks& h) {
    return solve_adr(p.physics(), p.loading, adr_options(p.scene.solver), u, h.progress, h.observe, h.adr_checkpoints,
                     h.adr_resume);
  };
  adr.keys.push_back({"check", d.check, "none | newton"});
  adr.checkpoint_state = "adr";
  SolverEntry verlet = row("verlet",
                     {{"dt", text(d.dt), "0: safety times the stable step"},
                      {"safety", text(d.safety), ""},
                      {"steps", std::to_string(d.steps), ""},
                      {"ramp_time", text(d.ramp_time), ""},
                      {"history_every", std::to_string(d.history_every), ""},
                      {"energy_check", d.energy_check ? "true" : "false", ""},
                      {"energy_tolerance", text(d.energy_tolerance), ""},
                      {"allow_unstable", d.allow_unstable ? "true" : "false", ""}},
                     d, false, true);
  verlet.dynamic = true;
  verlet.checkpoint_state = "verlet";
  verlet.solve = [](Problem& p, std::vector<double>& u, const SolveHooks& h) {
    std::vector<double> v;
    std::optional<SceneBreaking> breaking;
    if (p.scene.damage) breaking.emplace(p);
    SolveReport r;
    try {
      r = solve_verlet(p.physics(), p.loading, verlet_options(p.scene.solver), u, v, h.progress, h.observe,
                       h.verlet_checkpoints, h.verlet_resume, breaking ? &breaking->changes() : nullptr);
    } catch (const StableStepError& e) {
      // The masses and stiffnesses come from these keys (and dx, which scales both alike; a
      // plate's also from its thickness: mass rho t, stiffness E t^3).
      char plate[80] = "", keys[240];
      if (p.scene.model.type == "thin_plate")
        std::snprintf(plate, sizeof plate, " and geometry.thickness = %.4g m", p.scene.geometry.thickness);
      std::snprintf(keys, sizeof keys, "material.density = %.4g kg/m^3 with material.E = %.4g Pa%s give no time step: ",
                    p.scene.material.density, p.scene.material.E, plate);
      throw InputErrorOnEveryRank(p.scene.source + ": " + keys + e.what());
    }
    if (breaking) breaking->report(r, true);
    return r;
  };
  // Newton's own tolerances: its options struct's defaults, not ADR's.
  SolverSpec newton_defaults = d;
  newton_defaults.tolerance = NewtonOptions{}.tolerance;
  newton_defaults.max_iterations = NewtonOptions{}.max_iterations;
  SolverEntry newton = row("newton",
                     {{"tolerance", text(newton_defaults.tolerance), ""},
                      {"max_iterations", std::to_string(newton_defaults.max_iterations), ""},
                      {"load_steps", std::to_string(d.load_steps), ""},
                      {"line_search", d.line_search ? "true" : "false", ""},
                      {"linear_solver", d.linear_solver, "umfpack | klu | mumps | gamg (PETSc)"},
                      {"step_tolerance", text(d.step_tolerance), ""}},
                     newton_defaults, true, true);
  newton.jacobian = true;
  newton.iterations_of = "Newton";
  newton.solve = [](Problem& p, std::vector<double>& u, const SolveHooks& h) {
    return solve_newton(p.physics(), p.loading, newton_options(p), u, h.progress);
  };
  // One factorization of the reduced stiffness: linear, symmetric problems (direct.hpp).
  SolverSpec direct_defaults = d;
  direct_defaults.tolerance = DirectOptions{}.tolerance;
  SolverEntry direct = row("direct", {{"tolerance", text(direct_defaults.tolerance), "on the residual check"}},
                           direct_defaults, false, true);
  direct.jacobian = true;
  direct.iterations_of = "direct";
  direct.solve = [](Problem& p, std::vector<double>& u, const SolveHooks& h) {
    DirectOptions o;
    o.tolerance = p.scene.solver.tolerance;
    o.memory_limit = p.memory_limit;
    return solve_direct(p.physics(), p.loading, u, o, h.progress);
  };
  SolverEntry lbc = row("lbc", balance, d, true, false);
  lbc.keys.push_back({"yield_tolerance", text(d.yield_tolerance), ""});
  lbc.keys.push_back({"max_rounds", std::to_string(d.max_rounds), ""});
  lbc.keys.push_back({"check", d.check, "none | newton"});
  return {adr, verlet, newton, direct, lbc};
}

}  // namespace

const std::vector<ModelEntry>& model_registry() {
  static const std::vector<ModelEntry> table = make_models();
  return table;
}

const ModelEntry* find_model(const std::string& name) {
  for (const auto& e : model_registry())
    if (e.name == name) return &e;
  return nullptr;
}

const std::vector<SolverEntry>& solver_registry() {
  static const std::vector<SolverEntry> table = make_solvers();
  return table;
}

const SolverEntry* find_solver(const std::string& name) {
  for (const auto& e : solver_registry())
    if (e.name == name) return &e;
  return nullptr;
}

const SolverEntry& solver_of(const Scene& scene) {
  const SolverEntry* entry = find_solver(scene.solver.type);
  if (!entry) throw std::logic_error("solver.type " + scene.solver.type + " is not registered");
  return *entry;
}

std::string model_names() {
  std::string out;
  for (const auto& e : model_registry()) out += (out.empty() ? "" : ", ") + e.name;
  return out;
}

std::string solver_names_or() {
  const auto& t = solver_registry();
  std::string out;
  for (std::size_t k = 0; k < t.size(); ++k) out += (k == 0 ? "" : k + 1 == t.size() ? " or " : ", ") + t[k].name;
  return out;
}

AdrOptions adr_options(const SolverSpec& s) {
  AdrOptions o;
  o.tolerance = s.tolerance;
  o.displacement_tolerance = s.displacement_tolerance;
  o.max_iterations = s.max_iterations;
  o.load_steps = s.load_steps;
  o.history_every = s.history_every;
  return o;
}

VerletOptions verlet_options(const SolverSpec& s) {
  VerletOptions o;
  o.dt = s.dt;
  o.safety = s.safety;
  o.steps = s.steps;
  o.ramp_time = s.ramp_time;
  o.history_every = s.history_every;
  o.energy_check = s.energy_check;
  o.energy_tolerance = s.energy_tolerance;
  return o;
}

NewtonOptions newton_options(const SolverSpec& s) {
  NewtonOptions o;
  o.load_steps = s.load_steps;
  o.line_search = s.line_search;
  o.step_tolerance = s.step_tolerance;
  o.linear_solver = s.linear_solver;
  if (s.type == "newton") o.tolerance = s.tolerance, o.max_iterations = static_cast<int>(s.max_iterations);
  return o;
}

namespace {
/// GAMG's near-null space: a solid's rigid-body modes, from its particles' positions.
void add_positions(NewtonOptions& o, const Problem& p) {
  if (o.linear_solver != "gamg" || p.physics().dofs_per_particle() != p.cloud.dim) return;
  o.positions = p.cloud.x;
  o.dimension = p.cloud.dim;
}
}  // namespace

NewtonOptions newton_options(const Problem& p) {
  NewtonOptions o = newton_options(p.scene.solver);
  add_positions(o, p);
  o.memory_limit = p.memory_limit;
  return o;
}

LoadPathOptions load_path_options(const Problem& p) {
  LoadPathOptions o = load_path_options(p.scene.solver);
  add_positions(o.newton, p);
  o.newton.memory_limit = p.memory_limit;
  return o;
}

LoadPathOptions load_path_options(const SolverSpec& s) {
  LoadPathOptions o;
  parse_load_path_scheme(s.type, o.scheme);
  o.adr.tolerance = s.tolerance;
  o.adr.displacement_tolerance = s.displacement_tolerance;
  o.adr.max_iterations = s.max_iterations;
  o.newton.line_search = s.line_search;
  o.newton.linear_solver = s.linear_solver;
  o.newton.step_tolerance = s.step_tolerance;
  if (s.type == "newton") o.newton.tolerance = s.tolerance, o.newton.max_iterations = static_cast<int>(s.max_iterations);
  o.yield_tolerance = s.yield_tolerance;
  o.max_rounds = s.max_rounds;
  return o;
}

Problem build_problem(const Scene& s, PhaseTimer* timer) {
  const ModelEntry* entry = find_model(s.model.type);
  if (!entry) throw std::logic_error("build_problem: model.type " + s.model.type + " is not registered");
  return entry->build(s, timer);
}

SolveReport solve_problem(Problem& p, std::vector<double>& u, const SolveHooks& h) {
  const SolverSpec& spec = p.scene.solver;
  const SolverEntry* entry = find_solver(spec.type);
  if (!entry) throw std::logic_error("solve_problem: solver.type " + spec.type + " is not registered");
  if (p.scene.load_path()) {
    if (!entry->load_path) throw std::logic_error("solve_problem: " + spec.type + " does not solve load paths");
    std::optional<SceneBreaking> breaking;
    if (p.scene.damage) breaking.emplace(p);
    SolveReport r = solve_load_path(p.physics(), p.stages, load_path_options(p), u, h.progress, h.after_step,
                                    h.load_path_checkpoints, h.load_path_resume, breaking ? &breaking->changes() : nullptr);
    if (breaking) breaking->report(r, false);
    return r;
  }
  if (!entry->single) throw std::logic_error("solve_problem: " + spec.type + " solves load paths only");
  return entry->solve(p, u, h);
}

}  // namespace perinom

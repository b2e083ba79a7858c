#pragma once
/// @file The models and solvers a scene may name, in two tables: name -> factory, with the
/// scene keys each accepts and their defaults. The scene reader validates model.type and
/// solver.type against them; build_problem and solve_problem look the factory up. A new model
/// or solver is one new row (docs/architecture.md), and no driver changes.
#include <functional>
#include <string>
#include <vector>

#include "perinom/core/progress.hpp"
#include "perinom/core/timer.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/direct.hpp"
#include "perinom/solvers/load_path.hpp"
#include "perinom/solvers/newton.hpp"
#include "perinom/solvers/verlet.hpp"

namespace YAML {
class Node;
}

namespace perinom {
namespace detail {
class Fields;
}

/// A scene key of a model or solver section and its default, as the reader applies it
/// ("" for a key without a default, or whose default depends on other keys: then `note` says how).
struct OptionKey {
  std::string key;
  std::string default_value;
  std::string note;
};

/// What a model's build holds, measured (the peak resident bytes of perinom check less the
/// process before the build, docs/scene-format.md), for the memory estimate before building.
struct MemoryRates {
  double per_bond = 0.0;      ///< bytes per bond: operators, workspaces, the build's temporaries
  double per_particle = 0.0;  ///< bytes per particle beyond those (plastic states)
  bool nodes_on_edges = false;  ///< the lattice has a node on both ends of each axis (a plate)
};

/// A model.type: the keys of `model:` it reads (type aside), how it reads and checks them,
/// how it builds the problem, and what that build holds in memory.
struct ModelEntry {
  std::string name;
  std::vector<OptionKey> keys;
  /// Reads the `model:` section into scene.model (strict: an unknown key is an InputError).
  std::function<void(detail::Fields& section, Scene& scene)> read;
  /// Checks what the model needs of the other sections, after `model:` is read.
  std::function<void(const YAML::Node& root, const Scene& scene)> check;
  /// Builds the problem: particles, families, the model, loadings, probes.
  std::function<Problem(const Scene& scene, PhaseTimer* timer)> build;
  std::function<MemoryRates(const Scene& scene)> memory;
  /// Reads the model's keys of a boundary item into b (region, fix and displacement are read
  /// already) and finishes the item (strict).
  std::function<void(detail::Fields& item, const Scene& scene, BoundarySpec& b)> read_boundary;
  /// The field a probe measures when it names none. With probe_field_only, the model's
  /// probes measure that field alone, and no other model's probes may name it.
  std::string probe_field = "displacement";
  bool probe_field_only = false;
  /// Whether load stages, load-path schemes (solver.type lbc) and constraints: rigid_body
  /// apply to it (the messages for a model that takes none name it: "a thin_plate is ...").
  bool stages = true;
  bool load_path_schemes = true;
  bool rigid_body = true;
};

/// The registered models, in the order messages list them.
const std::vector<ModelEntry>& model_registry();
/// The entry of a model.type, or nullptr.
const ModelEntry* find_model(const std::string& name);

/// What a solve reports to, and resumes from: a progress line, snapshots every observe.every
/// iterations or steps, a load path's committed steps, and each solver's checkpoints and
/// resumed state (the one of the scene's solver is used, the others ignored).
struct SolveHooks {
  Progress* progress = nullptr;
  Observer observe;
  std::function<void(const LoadStepRecord&, const std::vector<double>&)> after_step;
  Checkpoints<AdrState> adr_checkpoints;
  const AdrState* adr_resume = nullptr;
  Checkpoints<VerletState> verlet_checkpoints;
  const VerletState* verlet_resume = nullptr;
  Checkpoints<LoadPathState> load_path_checkpoints;
  const LoadPathState* load_path_resume = nullptr;
};

/// A solver.type: the keys of `solver:` it reads with their defaults (`defaults`: a SolverSpec
/// holding them, the solver's options structs' own), and how it solves a problem's single
/// loading. A load-path scene (Scene::load_path) is solved by solve_load_path with the
/// scheme of the same name instead (`load_path`: the type is a load-path scheme).
struct SolverEntry {
  std::string name;
  std::vector<OptionKey> keys;
  SolverSpec defaults;
  bool load_path = false;   ///< solves load paths (stages, plasticity)
  bool single = false;      ///< solves a single loading
  std::function<SolveReport(Problem& p, std::vector<double>& u, const SolveHooks& hooks)> solve;
  bool dynamic = false;    ///< integrates in time: snapshots stamped with the time, no static checks
  bool jacobian = false;   ///< assembles the Jacobian (perinom check sizes it)
  /// The state its single-loading checkpoints hold ("adr", "verlet"), or "" when it is not
  /// checkpointed (a load path's is "load_path" whatever the scheme).
  std::string checkpoint_state;
  std::string iterations_of = "ADR";  ///< whose iterations a load path's summary line counts
};

const std::vector<SolverEntry>& solver_registry();
const SolverEntry* find_solver(const std::string& name);
/// The row of the scene's solver.type (the reader has checked it); std::logic_error otherwise.
const SolverEntry& solver_of(const Scene& scene);

/// "a, b, c or d" and "a, b, c" of the registered names, for messages.
std::string model_names();
std::string solver_names_or();

/// The solvers' options a scene's solver keys ask for (the Newton options also for the
/// Newton check: with another solver.type its tolerances are Newton's defaults).
AdrOptions adr_options(const SolverSpec& s);
VerletOptions verlet_options(const SolverSpec& s);
NewtonOptions newton_options(const SolverSpec& s);
LoadPathOptions load_path_options(const SolverSpec& s);
/// The same, with what the problem adds: the positions GAMG's near-null space is built from.
NewtonOptions newton_options(const Problem& p);
LoadPathOptions load_path_options(const Problem& p);

/// Solves the problem by its scene's solver into u (resized to the model's dofs): a load
/// path for Scene::load_path(), else the solver entry's single-loading solve.
SolveReport solve_problem(Problem& p, std::vector<double>& u, const SolveHooks& hooks = {});

}  // namespace perinom

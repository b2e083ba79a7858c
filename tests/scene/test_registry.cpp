// The model and solver registries (scene/registry.hpp): every registered name builds and
// solves, unknown names are refused with the list of valid ones, and the defaults the scene
// reader applies are the table's.
#include <catch2/catch.hpp>

#include <map>
#include <set>

#include "perinom/core/error.hpp"
#include "perinom/scene/registry.hpp"
#include "../support/pulled_bar.hpp"
#include "../support/small_plate.hpp"

using namespace perinom;

namespace {

/// A small valid scene for each registered model; a model added to the registry without one
/// here fails the first test.
const std::map<std::string, std::string> model_scenes = {
    {"correspondence", test::pulled_bar},
    {"thin_plate", test::small_plate}};

std::string message_of(const std::string& text) {
  try {
    parse_scene(text, "registry.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("every registered model builds a problem and answers through Model alone", "[scene][registry]") {
  std::set<std::string> registered;
  for (const ModelEntry& entry : model_registry()) {
    INFO("model.type " << entry.name);
    registered.insert(entry.name);
    REQUIRE(model_scenes.count(entry.name) == 1);
    const Scene scene = parse_scene(model_scenes.at(entry.name), entry.name + ".yaml");
    CHECK(scene.model.type == entry.name);
    REQUIRE(entry.memory);
    CHECK(entry.memory(scene).per_bond > 0.0);
    Problem p = build_problem(scene);
    REQUIRE(p.model != nullptr);
    const Model& model = p.physics();
    CHECK(model.particles() == p.cloud.size());
    const std::vector<double> u(model.dofs(), 0.0);
    const std::vector<OutputField> fields = model.output_fields(u.data());
    REQUIRE_FALSE(fields.empty());
    for (const auto& f : fields) CHECK(f.values.size() == model.particles() * std::size_t(f.components));
    CHECK_FALSE(model.plan().empty());
    CHECK_FALSE(model.not_assembled().empty());
    CHECK(model.stress_measure(u.data()).size() % model.particles() == 0);
  }
  CHECK(registered.size() == model_scenes.size());
  CHECK(find_model("no_such_model") == nullptr);
}

TEST_CASE("every registered solver solves the pulled bar through solve_problem", "[scene][registry]") {
  for (const SolverEntry& entry : solver_registry()) {
    INFO("solver.type " << entry.name);
    const std::string extra = entry.name == "verlet" ? ", steps: 20" : "";
    Problem p = build_problem(parse_scene(test::pulled_bar + "solver: {type: " + entry.name + extra + "}\n", "bar.yaml"));
    CHECK(p.scene.load_path() == (entry.load_path && !entry.single));
    std::vector<double> u(p.physics().dofs(), 0.0);
    const SolveReport rep = solve_problem(p, u);
    CHECK(rep.failure.empty());
    if (entry.name != "verlet") CHECK(rep.converged);
  }
}

TEST_CASE("an unknown model or solver is refused naming the key and listing the registered names",
          "[scene][registry]") {
  CHECK(model_names() == "correspondence, thin_plate");
  CHECK(solver_names_or() == "adr, verlet, newton, direct or lbc");
  const std::string model = message_of(test::pulled_bar + "model: {type: peridigm}\n");
  CHECK(model.find("model.type") != std::string::npos);
  CHECK(model.find("unknown model type (known: " + model_names() + ")") != std::string::npos);
  const std::string solver = message_of(test::pulled_bar + "solver: {type: cg}\n");
  CHECK(solver.find("solver.type") != std::string::npos);
  CHECK(solver.find("must be " + solver_names_or()) != std::string::npos);
}

TEST_CASE("the defaults the scene reader applies are the registry's and the solvers' own", "[scene][registry]") {
  SECTION("solvers: each solver's row, from its options struct") {
    for (const SolverEntry& entry : solver_registry()) {
      INFO("solver.type " << entry.name);
      const Scene s = parse_scene(test::pulled_bar + "solver: {type: " + entry.name + "}\n", "bar.yaml");
      CHECK(s.solver.tolerance == entry.defaults.tolerance);
      CHECK(s.solver.max_iterations == entry.defaults.max_iterations);
      CHECK(s.solver.displacement_tolerance == entry.defaults.displacement_tolerance);
      CHECK(s.solver.yield_tolerance == entry.defaults.yield_tolerance);
      for (const OptionKey& key : entry.keys) CHECK_FALSE(key.key.empty());
    }
    CHECK(find_solver("newton")->defaults.tolerance == NewtonOptions{}.tolerance);
    CHECK(find_solver("newton")->defaults.max_iterations == NewtonOptions{}.max_iterations);
    CHECK(find_solver("adr")->defaults.tolerance == AdrOptions{}.tolerance);
    CHECK(find_solver("adr")->defaults.max_iterations == AdrOptions{}.max_iterations);
    CHECK(find_solver("verlet")->defaults.safety == VerletOptions{}.safety);
    CHECK(find_solver("verlet")->dynamic);
    CHECK(find_solver("newton")->jacobian);
    CHECK(find_solver("newton")->checkpoint_state.empty());
    CHECK(find_solver("adr")->checkpoint_state == "adr");
  }
  SECTION("the options structs the solvers receive are the spec's") {
    const Scene newton = parse_scene(test::pulled_bar + "solver: {type: newton, tolerance: 1e-9}\n", "bar.yaml");
    CHECK(newton_options(newton.solver).tolerance == 1e-9);
    CHECK(newton_options(newton.solver).max_iterations == NewtonOptions{}.max_iterations);
    // The Newton check of an ADR solve runs Newton with Newton's own tolerances.
    const Scene adr = parse_scene(test::pulled_bar + "solver: {type: adr, tolerance: 1e-7}\n", "bar.yaml");
    CHECK(newton_options(adr.solver).tolerance == NewtonOptions{}.tolerance);
    CHECK(adr_options(adr.solver).tolerance == 1e-7);
    CHECK(load_path_options(adr.solver).adr.tolerance == 1e-7);
  }
  SECTION("models: the keys listed with a default are read with it") {
    const Scene s = parse_scene(test::pulled_bar, "bar.yaml");
    const ModelEntry& correspondence = *find_model("correspondence");
    const std::map<std::string, std::string> read = {{"formulation", s.model.formulation},
                                                     {"stabilization", "0.5"},
                                                     {"stabilization_storage", s.model.stabilization_storage},
                                                     {"stabilization_scale", s.model.stabilization_scale},
                                                     {"weight_precision", s.model.weight_precision},
                                                     {"kinematics", s.model.kinematics}};
    CHECK(s.model.stabilization == 0.5);
    for (const OptionKey& key : correspondence.keys) {
      INFO("model." << key.key);
      if (!key.default_value.empty()) CHECK(read.at(key.key) == key.default_value);
    }
  }
}

TEST_CASE("the keys a model's row lists are the keys its reader reads, and no other", "[scene][registry]") {
  for (const ModelEntry& entry : model_registry()) {
    // The scene without its model section, then one model section per probe.
    std::string base = model_scenes.at(entry.name);
    const std::size_t at = base.find("\nmodel:");
    if (at != std::string::npos) base.erase(at + 1, base.find('\n', at + 1) - at);
    const auto with_model = [&](const std::string& extra) {
      return base + "model: {type: " + entry.name + extra + "}\n";
    };
    INFO("model.type " << entry.name);
    REQUIRE(message_of(with_model("")).empty());
    for (const OptionKey& key : entry.keys) {
      // A list where every key of a model takes a scalar: read, hence refused by its name.
      const std::string m = message_of(with_model(", " + key.key + ": [1, 2]"));
      INFO("model." << key.key << ": " << m);
      CHECK(m.find("model." + key.key) != std::string::npos);
      CHECK(m.find("unknown key") == std::string::npos);
    }
    CHECK(message_of(with_model(", not_a_key: 1")).find("model.not_a_key: unknown key") != std::string::npos);
  }
}

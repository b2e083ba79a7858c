#pragma once
/// @file What a scene file asks for. Field names mirror the YAML keys
/// (docs/scene-format.md documents them key by key); defaults are in-class.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "perinom/fracture/precrack.hpp"
#include "perinom/geometry/lattice.hpp"
#include "perinom/geometry/plate_cloud.hpp"
#include "perinom/geometry/region.hpp"
#include "perinom/materials/drucker_prager.hpp"
#include "perinom/materials/linear_elastic.hpp"
#include "perinom/operators/influence.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/load_path.hpp"
#include "perinom/solvers/newton.hpp"
#include "perinom/solvers/verlet.hpp"

namespace perinom {

/// geometry.mesh, or geometry.points with an optional geometry.facets: a body read from files
/// instead of a lattice filling geometry.box. Paths are resolved against the scene file's folder.
struct BodyFiles {
  std::string mesh;    ///< a gmsh .msh file (format 4.1, ASCII)
  std::string points;  ///< a CSV of particles (x, y[, z], volume)
  std::string facets;  ///< a CSV of boundary facets for `points`
  std::string where;   ///< "file:line: geometry.mesh" (or .points) for messages
  std::string facets_where;  ///< "file:line: geometry.facets" for messages
  bool given() const { return !mesh.empty() || !points.empty(); }
};

struct DiscretizationSpec {
  double dx = 0.0;            ///< m
  double horizon_ratio = 0.0; ///< delta = ratio * dx (radius families), or
  int horizon_neighbors = 0;  ///< k nearest neighbours
  Influence weight = Influence::inverse_square;
  double jitter = 0.0;        ///< random offsets, fraction of the spacing
  std::uint64_t seed = 1;
};

struct ModelSpec {
  std::string type = "correspondence";  ///< correspondence | thin_plate
  std::string formulation = "consistent";
  double stabilization = 0.5;  ///< C_hg (thin_plate: of the operator energy)
  std::string stabilization_storage = "auto";  ///< auto | fused | assembled | matrix_free
  std::string stabilization_scale = "elastic";  ///< elastic | secant (drucker_prager: S follows the secant stiffness)
  std::string weight_precision = "double";          ///< double | single (G's stored weights)
  std::string kinematics = "small_strain";  ///< small_strain | finite_rotation (plasticity)
  bool follower_pressure = false;  ///< pressures follow the deformed surface (finite_rotation; its default)
  int operator_order = 2;  ///< 1 | 2 (default 2 with the consistent formulation, 1 otherwise): the fit G comes from (CorrespondenceOptions::operator_order)
};

/// One boundary condition on a region. Each of the three may be given: components to
/// fix (at zero, or at a prescribed ramped displacement), a traction vector, a pressure.
struct BoundarySpec {
  std::string where;  ///< "file:line: boundary[k]" for messages
  std::string key;    ///< "boundary.k" or "stages.s.boundary.k": names its reaction
  Region region;
  std::array<bool, 3> fix{false, false, false};
  std::array<std::optional<double>, 3> displacement;  ///< m, at full load
  std::array<std::optional<double>, 3> velocity;      ///< m/s from t = 0 (Verlet, at the particles)
  std::optional<std::array<double, 3>> traction;      ///< Pa, on a side
  std::optional<double> pressure;                     ///< Pa, positive pushes inward
  bool at_face = false;  ///< displacements prescribed at the box face, not at the particles
  std::optional<EdgeSupport> support;  ///< thin_plate: how the side is held
};

/// One stage of a load path (`stages:`): its own boundary conditions, added to the scene's
/// `boundary` list, applied in `steps` load steps from where the previous stage ended.
struct StageSpec {
  std::string where;
  std::string name;
  int steps = 1;
  std::vector<BoundarySpec> boundary;
};

/// The `solver:` keys. The defaults are the solvers' options structs' own (one place); a
/// solver whose defaults differ (newton: tolerance, max_iterations) has them in its
/// registry row (registry.hpp), which the reader starts from.
struct SolverSpec {
  std::string type = "adr";  ///< a registered solver: adr | verlet | newton | lbc
  double tolerance = AdrOptions{}.tolerance;
  double displacement_tolerance = AdrOptions{}.displacement_tolerance;
  std::int64_t max_iterations = AdrOptions{}.max_iterations;
  int load_steps = AdrOptions{}.load_steps;
  double dt = VerletOptions{}.dt;  ///< Verlet: 0 picks the stable step times safety
  double safety = VerletOptions{}.safety;
  std::int64_t steps = VerletOptions{}.steps;
  double ramp_time = VerletOptions{}.ramp_time;
  std::int64_t history_every = AdrOptions{}.history_every;
  bool line_search = NewtonOptions{}.line_search;        ///< Newton
  std::string linear_solver = NewtonOptions{}.linear_solver;  ///< Newton: umfpack | klu | mumps | gamg
  double step_tolerance = NewtonOptions{}.step_tolerance;  ///< Newton: KINSOL's scaled step tolerance
  std::string check = "none"; ///< "newton": also solve with Newton and report the difference
  double yield_tolerance = LoadPathOptions{}.yield_tolerance;  ///< LBC: relative violation of the yield condition that flags
  int max_rounds = LoadPathOptions{}.max_rounds;               ///< LBC: balance-correction rounds per load step
  bool energy_check = VerletOptions{}.energy_check;          ///< Verlet: stop when the energy balance fails
  double energy_tolerance = VerletOptions{}.energy_tolerance;  ///< Verlet: the balance's allowed share of the largest energy or work
  bool allow_unstable = false;    ///< Verlet: run the improved or strong formulation anyway
};

/// The `damage:` keys (issue 17): which bonds break during a Verlet run (THEORY sec. 10).
struct DamageSpec {
  std::string criterion;   ///< instability | stretch | stress
  double s_max = 0.0;      ///< instability: the largest bond stretch that arms it
  double s_c = 0.0;        ///< stretch: the critical stretch (given, or derived from G_c when the problem is built)
  double G_c = 0.0;        ///< stretch: the fracture energy (J/m^2) s_c is derived from; 0 when s_c is given
  double G_c_delta = 0.0;  ///< the horizon the derivation used (m): the median family radius
  double f_t = 0.0;        ///< stress: the tensile strength (Pa)
  double fracture_energy = 0.0;  ///< stress: G_f (J/m^2), broken bonds soften (models/cohesive_bonds.hpp); 0: they vanish
  std::int64_t every = 1;  ///< look for bonds to break every this many steps
  std::vector<Region> no_fail;  ///< bonds with an end in one of these never break (box, side or point regions)
  std::vector<std::string> no_fail_where;  ///< "file:line: damage.no_fail[k]" for messages
};

struct ProbeSpec {
  std::string where;  ///< "file:line: probes[k]" for messages
  std::string name;
  bool is_line = false;
  std::array<double, 3> point{0, 0, 0}, from{0, 0, 0}, to{0, 0, 0};
  /// displacement | stress | von_mises | mean_stress | equivalent_strain | eq_plastic_strain;
  /// thin_plate: deflection
  std::string field = "displacement";
  std::string component = "x";         ///< x|y|z, or xx|yy|zz|xy|yz|xz for stress
  bool reconstruct = false;  ///< point displacement probes: u_i + (grad u)_i (x - x_i) at the point
};

struct OutputSpec {
  std::int64_t vtk_every = 0;  ///< VTK snapshots every this many iterations (load steps on a
                               ///< load path); 0: the final state only
  std::vector<std::int64_t> vtk_steps;  ///< load paths: snapshots after these load steps (counted over all stages)
  bool csv = false;  ///< each snapshot's point data also as CSV
  /// A checkpoint (checkpoint.bin) every this many ADR iterations, Verlet steps or load
  /// steps; 0: none. Newton solves are not checkpointed (refused).
  std::int64_t checkpoint_every = 0;
};

struct Scene {
  std::string source;  ///< file name, for messages
  /// The scene's YAML after the --set overrides, without its `output` section, as yaml-cpp
  /// writes it: what a checkpoint must have been written for (scene_difference.hpp).
  std::string canonical;
  std::string name;
  int dim = 2;
  BoxGeometry geometry;  ///< the box (and holes) of a lattice; dim and thickness for every body
  BodyFiles body_files;  ///< a mesh or a point file instead of the box
  DiscretizationSpec discretization;
  LinearElastic material;  ///< the elastic moduli (of the plastic law too) and the density
  std::optional<DruckerPrager> plasticity;  ///< material.type: drucker_prager
  ModelSpec model;
  std::vector<BoundarySpec> boundary;
  std::vector<StageSpec> stages;  ///< empty: one stage of solver.load_steps steps
  /// none | rigid_body: pins chosen to remove the rigid modes of a body loaded by balanced
  /// tractions only (rigid_body_pins)
  std::string constraints = "none";
  SolverSpec solver;
  OutputSpec output;
  std::vector<ProbeSpec> probes;
  std::optional<DamageSpec> damage;  ///< `damage:`; none: no bond breaks during the run
  std::vector<Precrack> precracks;   ///< `precracks:`, cut at build time

  /// Solved as a quasi-static load path (solvers/load_path.hpp): a plastic material,
  /// stages, or solver.type lbc.
  bool load_path() const { return plasticity.has_value() || !stages.empty() || solver.type == "lbc"; }
  /// Whether `which(item)` holds for a boundary item of the scene or of one of its stages.
  template <class Which>
  bool any_boundary(Which which) const {
    for (const BoundarySpec& b : boundary)
      if (which(b)) return true;
    for (const StageSpec& stage : stages)
      for (const BoundarySpec& b : stage.boundary)
        if (which(b)) return true;
    return false;
  }
};

/// Reads and validates a scene file, after applying `--set dotted.key=value` overrides
/// (list items by index: boundary.0.pressure=1e5). Throws InputError naming the key
/// (and line) of the first problem found.
Scene read_scene(const std::string& path, const std::vector<std::string>& overrides = {});
/// The same for a scene held in a string (source names it in messages).
Scene parse_scene(const std::string& text, const std::string& source,
                  const std::vector<std::string>& overrides = {});

}  // namespace perinom

#pragma once
/// @file A scene turned into what the solvers consume: particles, families, the assembled
/// model, the loading and the resolved probes.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "perinom/core/error.hpp"
#include "perinom/core/timer.hpp"
#include "perinom/geometry/body.hpp"
#include "perinom/materials/measures.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/models/rigid_body.hpp"
#include "perinom/models/thin_plate.hpp"
#include "perinom/scene/scene.hpp"

namespace perinom {

/// A probe bound to particles: the nearest particle of a point, or the particles within half
/// a spacing of a line segment ordered along it (s = distance from `from`, m).
struct BoundProbe {
  ProbeSpec spec;
  std::vector<ParticleId> particles;
  std::vector<double> along;
};

/// One model slot: the model model.type names (registry.hpp builds it), used by the solvers
/// and the drivers through TangentModel and Model alone. A feature that is truly one model's
/// is reached by typed access, as<CorrespondenceModel>().
struct Problem {
  Scene scene;
  PointCloud cloud;  ///< the particles the solvers, probes and snapshots see (a plate: its nodes, no ghosts)
  std::size_t bonds = 0;
  std::unique_ptr<TangentModel> model;
  Loading loading;                 ///< the scene's `boundary` at solver.load_steps (single-stage solvers)
  std::vector<LoadStage> stages;   ///< load-path scenes (Scene::load_path): one per stage
  std::vector<BoundProbe> probes;
  /// constraints: rigid_body: the pins added to every loading (support "rigid_body").
  std::vector<RigidBodyPin> pins;
  /// A body from geometry.mesh or geometry.points: its facet groups, its element count (0: not
  /// a mesh), its mean element size (m) and how far its facets miss the divergence theorem
  /// (divergence_theorem_defect; 0 when it has no facets).
  std::vector<FacetGroup> groups;
  std::size_t mesh_elements = 0;
  double mean_size = 0.0;
  double facet_defect = 0.0;
  /// The boundary facets, by particle of the whole cloud, that the loads and the consistent
  /// formulation see (a body from files: its own; a lattice: lattice_facets under the
  /// consistent formulation, else none): the ranks' parts take their share of the frame's,
  /// and the thin-body note measures the body's thickness on them.
  BoundaryFacets facets;
  /// The bytes the run may hold (the command line's --max-memory); 0: the memory available.
  /// Newton with umfpack or klu, and solver.type direct, check their factors' predicted size
  /// against it before factoring (lib/solvers/factor_memory.hpp).
  double memory_limit = 0.0;

  TangentModel& physics() { return *model; }
  const TangentModel& physics() const { return *model; }
  /// The model as its concrete type; throws std::logic_error when it is another.
  template <class M>
  M& as() const {
    M* m = dynamic_cast<M*>(model.get());
    if (!m) throw std::logic_error("Problem::as: the scene's model is of another type");
    return *m;
  }
};

/// Binds a probe to the cloud's particles; throws InputError for a line that meets none, a
/// point off the body, or (given the box) a point inside one of its holes.
BoundProbe bind_probe(const ProbeSpec& spec, const PointCloud& cloud, const BoxGeometry* box = nullptr);

/// "discretization.horizon.neighbors" or "discretization.horizon.ratio", for messages.
std::string horizon_key(const Scene& scene);
/// "SOURCE: <horizon_key>: what", and when a radius horizon is over a lattice whose spacing
/// the box's whole cells made larger than dx, why that matters: delta = ratio x dx then spans
/// fewer spacings than the ratio says (a plate at dx 12.4 mm on a 0.5 m side, spacing 12.5 mm,
/// lost its second ring and blamed a ghost node).
std::string horizon_error(const Scene& scene, const PointCloud& cloud, const std::string& what);
/// The families discretization.horizon asks for on the cloud; errors name that key.
Families scene_families(const Scene& scene, const PointCloud& cloud);

/// Builds a correspondence or a thin_plate scene's problem (their rows of the model
/// registry, registry.hpp; build_problem looks the row up).
Problem build_correspondence_problem(const Scene& scene, PhaseTimer* timer);
Problem build_plate_problem(const Scene& scene, PhaseTimer* timer);

/// The model options a correspondence scene asks for (model, discretization.weight, plasticity,
/// damage's fields).
CorrespondenceOptions correspondence_options(const Scene& scene);

/// What every rank of a distributed run shares (issue 19): the scene's particles, its loading
/// and bound probes, without families or a model (p.model is null). A correspondence scene of
/// the classical or consistent formulation: throws std::logic_error for another, which the
/// caller refuses first. `constraints: rigid_body` pins it (p.pins) as a serial run would.
/// The loads' balance is checked here for the classical formulation only (the consistent
/// one's tractions act at the faces: its ranks check their own, require_balanced_loads).
/// The loading's face-located constraints are not coupled yet (a rank
/// couples its own: rank_loading.hpp); its forces are the classical formulation's (at the
/// outer layer), and a consistent run takes its own from its trace (rank_loading.hpp). A body
/// from files keeps its facets (p.facets) for the ranks' shares.
Problem build_problem_frame(const Scene& scene);

/// constraints: rigid_body's check of the loads: `resultants` are the scene's loading's, then
/// each stage's (p.stages' order), of the forces the run applies; throws InputError naming
/// the first that is not balanced. `layer_loads`: the tractions act at the outer layer's
/// particles (the message says why their moments need not cancel).
void require_balanced_loads(const Problem& p, const std::vector<LoadResultant>& resultants, bool layer_loads);

/// constraints: rigid_body's refusal of a body in `count` pieces, `second` the smallest
/// particle not in particle 0's piece.
InputError rigid_body_pieces_error(const Scene& scene, std::int64_t count, std::int64_t second);

/// The boundary items of load stage k (p.stages[k]): the scene's own and the stage's (a
/// load path without stages has one stage, of the scene's items).
std::vector<BoundarySpec> stage_boundary(const Scene& scene, std::size_t k);

/// Builds the problem (lattice, families, operators, loading, probes) by the model registry's
/// row of model.type (registry.cpp). Phases are timed
/// in `timer` when given. Throws InputError for a region that selects no particle, a
/// singular shape tensor, or (constraints: rigid_body) loads that are not balanced.
Problem build_problem(const Scene& scene, PhaseTimer* timer = nullptr);

/// The fields probes read: displacement u (N x d), 3 x 3 stresses sigma (N x 9), the
/// displacement gradient H (N x d x d), and the committed xi per particle (or nullptr).
struct ProbeFields {
  const PointCloud& cloud;
  const std::vector<double>& u;
  const std::vector<double>& sigma;
  const std::vector<double>& H;
  /// grad sigma (N x 9 x d, stress_gradient), needed by reconstructed stress probes only.
  const std::vector<double>* grad_sigma = nullptr;
  /// The committed xi per particle (nullptr: 0).
  const std::vector<double>* eq_plastic_strain = nullptr;
  /// Any other field a probe names (a plate's deflection), by name.
  const std::vector<OutputField>* fields = nullptr;
};

/// The probes' view of a state, for any model: its output fields at u (Model::output_fields
/// with the probe fields, and the gradients when a point probe reconstructs a stress field).
class ProbeReadout {
 public:
  ProbeReadout(const Problem& p, const std::vector<double>& u);
  /// The field of that name, or nullptr.
  const OutputField* find(const std::string& name) const;
  /// A scalar field's value at particle i; 0 when the model has no such field.
  double scalar(const std::string& name, std::size_t i) const;
  /// A point probe's value (point_probe_value), and a probe's field at particle i (probe_value).
  double point(const BoundProbe& probe) const;
  double at(const ProbeSpec& spec, std::size_t i) const;
  /// A line probe's CSV: s, x, y, z, then (a model with a von Mises stress) ux, uy, uz,
  /// von_mises and value, else the probe's field alone under its name.
  std::vector<std::string> line_header(const ProbeSpec& spec) const;
  std::vector<double> line_row(const BoundProbe& probe, std::size_t k) const;

 private:
  const Problem& p_;
  const std::vector<double>& u_;
  std::vector<OutputField> fields_;
  std::vector<double> none_;
  ProbeFields view_;
};

/// True for the fields computed from the stress alone (stress, von_mises, mean_stress): those
/// a point probe reconstructs from the stress and its gradient.
bool stress_field(const std::string& field);

/// The nonlocal gradient of the 3 x 3 stresses sigma (N x 9) by the model's operator G:
/// out[(i*9 + c)*d + b] = d sigma_c / d x_b at particle i (Pa/m). Exact for linear stress
/// fields when G is exact for quadratic displacements (operator order 2, classical).
std::vector<double> stress_gradient(const CorrespondenceModel& model, const std::vector<double>& sigma);

/// sigma(y) = sigma_i + (grad sigma)_i (y - x_i) (9 values) at the point y (d values).
void reconstruct_stress(const std::vector<double>& sigma, const std::vector<double>& grad_sigma,
                        const PointCloud& cloud, std::size_t i, const double* y, double* out);

/// The value of a stress field (stress_field(spec.field)) of a 3 x 3 stress.
double stress_probe_value(const ProbeSpec& spec, const double* sigma3);


/// The value of a probe's field at particle i (SI units).
double probe_value(const ProbeSpec& spec, std::size_t i, const ProbeFields& f);

/// A point probe's value: at its nearest particle, or, with `reconstruct`, at the probe's
/// point through that particle's first-order reconstruction: u_i + (grad u)_i (x - x_i) for
/// the displacement; for a stress field, the field of sigma_i + (grad sigma)_i (x - x_i)
/// (needs f.grad_sigma; throws std::logic_error without it).
double point_probe_value(const BoundProbe& probe, const ProbeFields& f);

}  // namespace perinom

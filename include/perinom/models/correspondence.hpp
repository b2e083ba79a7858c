#pragma once
/// @file Correspondence (non-ordinary state-based) peridynamics (THEORY sec. 3-5).
/// classical: the weak form everywhere, f = G^T (V . P(G u)) + S u.
/// improved:  the weak form in D; in the band E within 2 delta of the surface the strong
///            form f_i = -V_i [(div P)_i - P_i m_i] (m_i the surface normal over the layer
///            thickness, zero inside), plus S u. Tractions remain loads t V / h (pressures
///            optionally follow the deformed surface: follower_pressure.hpp).
/// strong:    the strong form at every particle (E = everything), exact for uniform stress
///            on irregular clouds too.
/// consistent (the default of scenes): the weak form everywhere with the variationally
///            consistent gradient G~ (consistent_gradient.hpp), f = G~^T (V . P(G~ u)) + S u,
///            and tractions as work-consistent loads at the boundary facets (boundary_trace.hpp).
///            Symmetric and positive semi-definite like classical, with the surface effect
///            removed: the uniform-stress patch test is exact on any cloud whose facets close
///            the body. improved and strong are not symmetric: their strong-form rows can make
///            the discrete problem unstable (complex or negative eigenvalues of M^-1 K), which
///            is why they are no longer the default (docs/theory.md).
#include <functional>
#include <memory>
#include <optional>

#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/geometry/surface.hpp"
#include "perinom/materials/linear_elastic.hpp"
#include "perinom/models/cohesive_bonds.hpp"
#include "perinom/models/follower_pressure.hpp"
#include "perinom/models/model_history.hpp"
#include "perinom/models/local_model.hpp"
#include "perinom/models/finite_rotation.hpp"
#include "perinom/models/plastic_points.hpp"
#include "perinom/models/pointwise_law.hpp"
#include "perinom/neighbors/families.hpp"
#include "perinom/operators/boundary_trace.hpp"
#include "perinom/operators/consistent_gradient.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
#include "perinom/operators/bond_weights.hpp"
#include "perinom/operators/influence.hpp"
#include "perinom/operators/stabilization_term.hpp"
#include "perinom/operators/tangent_rows.hpp"

namespace perinom {

enum class Formulation { classical, improved, strong, consistent };

/// Parses "classical", "improved", "strong", "consistent"; false if unknown.
bool parse_formulation(const std::string& name, Formulation& f);

/// The assembly level of S (stabilization_term.hpp), or automatic: fused when the families
/// are symmetric, assembled otherwise.
enum class StabilizationStorage { automatic, fused, assembled, matrix_free };
/// Parses "auto", "fused", "assembled", "matrix_free"; false if unknown.
bool parse_stabilization_storage(const std::string& name, StabilizationStorage& s);

/// Options of the correspondence model.
struct CorrespondenceOptions {
  Influence influence = Influence::inverse_square;
  double stabilization = 0.5;  ///< C_hg (dimensionless); 0 assembles no S
  Formulation formulation = Formulation::classical;
  /// How the explicit force applies S (the answers agree to rounding):
  StabilizationStorage stabilization_storage = StabilizationStorage::automatic;
  /// Storage of G's weights (the stabilization and tangents use them as stored).
  WeightPrecision weight_precision = WeightPrecision::float64;
  /// 1: G from the first-order fit (THEORY sec. 2), stabilized by S (sec. 4).
  /// 2: G from the gradient weights of the second-order fit (sec. 6; exact for quadratic
  ///    fields, boundary particles included), stabilized by the second-order operator energy
  ///    (seed 002 eq. 35-39, operators/stabilization.hpp): assembled (the fit's Hessian
  ///    weights serve only to assemble S and are not kept) or matrix_free (the fit is kept).
  int operator_order = 1;
  /// With plasticity: each particle's stabilization follows its committed secant shear
  /// stiffness (c_i times PlasticPoints::secant_ratios, set as each load step begins), so S does
  /// not resist plastic flow as an elastic body would. Needs a matrix-free S (automatic
  /// storage chooses it): operator order 2, or order 1 with the classical formulation.
  bool secant_stabilization = false;
  /// A Drucker-Prager law in place of the linear elastic one (its E and nu must be the
  /// material's; the stabilization and the explicit solvers' mass use the elastic moduli).
  /// Any other law is given to the constructor (PointwiseLaw).
  std::optional<DruckerPrager> plasticity;
  /// finite_rotation: the plastic law inside a FiniteRotationLaw.
  Kinematics kinematics = Kinematics::small_strain;
  /// Pressures follow the deformed surface (follower_pressure.hpp); finite_rotation only.
  bool follower_pressure = false;
  /// Output fields of a run with cracks from its start: damage and max_principal_stress
  /// (otherwise damage appears once a bond is broken).
  bool fracture_fields = false;
  /// The consistent formulation on a distributed rank's local part: the rank's share of the
  /// correction solve (consistent_gradient.hpp); nullptr: the whole body.
  const CorrectionShare* ranks = nullptr;
  /// A distributed rank's local part: the rows fitted (its owned and near ones,
  /// OperatorOptions::fitted_rows); the far ghosts' truncated families are not fitted.
  std::size_t fitted_rows = SIZE_MAX;
};

/// What CorrespondenceModel::break_bonds did.
struct BondBreaks {
  std::size_t broken = 0;             ///< bonds that died (a pair counts once)
  std::vector<ParticleId> rows;       ///< the rows of G (and S) refreshed
  std::vector<ParticleId> detached;   ///< every particle detached so far (no stress, no force)
  double released = 0.0;              ///< break_bonds at a state u: the strain energy released there (J)
};

class CorrespondenceModel : public LocalModel, public ModelHistory {
 public:
  /// Assembles G (and S when C_hg > 0) once. Throws InputError for a singular shape tensor
  /// (or second-order fit), or a stabilization storage the operator order cannot use.
  /// The improved and strong formulations need the surface data (find_surface), the
  /// consistent one the boundary facets (lattice_facets). The consistent formulation stores S
  /// assembled, or at operator order 2 matrix-free (the fused and first-order matrix-free
  /// forms rest on G's first-order identities, which the corrected G has not).
  /// The pointwise law: `law` when given (its dim() and size() must be the cloud's; the
  /// material then only gives the elastic moduli of S, the mass and the stiffness bound),
  /// otherwise Drucker-Prager points (options.plasticity) or the material's ElasticPoints.
  CorrespondenceModel(const PointCloud& cloud, const Families& families,
                      const LinearElastic& material, const CorrespondenceOptions& options,
                      Surface surface = {}, BoundaryFacets facets = {},
                      std::unique_ptr<PointwiseLaw> law = nullptr);
  // The stabilization refers to this object's G: no copies, no moves.
  CorrespondenceModel(const CorrespondenceModel&) = delete;
  CorrespondenceModel& operator=(const CorrespondenceModel&) = delete;

  std::size_t particles() const override { return volume_.size(); }
  int dofs_per_particle() const override { return dim_; }
  void internal_force(const double* u, double* f) override;
  double energy(const double* u) override;
  std::vector<double> lumped_mass() const override;
  std::vector<double> stiffness_row_sums() const override;
  /// The same for the listed particles' rows only (sorted, distinct; d values each), as
  /// they are after break_bonds: a fracture run's stable time step follows its breaks by them,
  /// a distributed rank's by its owned rows. The classical and consistent formulations (no
  /// strong rows) only; throws std::logic_error else.
  std::vector<double> stiffness_row_sums(const std::vector<ParticleId>& rows) const override;
  std::vector<std::pair<std::string, std::size_t>> memory() const override;
  void follow_loads(const Loading& loading, double s) override;

  /// Visits the block rows of the stiffness dF/du (THEORY sec. 3-5): the weak rows
  /// G^T (V . C) G, the strong rows of the band E for the improved and strong formulations,
  /// plus S. See for_each_tangent_row for the arguments of visit.
  void visit_tangent_rows(const TangentRowVisitor& visit) const override;
  /// The same for the listed rows only (sorted, distinct; their columns sorted), at the
  /// last prepare_tangent: a distributed rank's own rows. The classical and consistent
  /// formulations without follower loads only (throws std::logic_error else).
  void visit_tangent_rows(const std::vector<ParticleId>& rows, const TangentRowVisitor& visit) const override;

  /// A distributed rank's local model (neighbors/local_part.hpp): internal_force evaluates
  /// grad u and the law on the first `evaluated` particles (owned and near ghosts) and writes
  /// the force of the first `written` (owned), zero on the others, and energy() sums the
  /// written particles' share; only those rows are then meaningful. The classical formulation only (the others' rows read the whole body):
  /// throws std::logic_error else.
  void limit_rows(std::size_t evaluated, std::size_t written) override;

  /// grad u at every particle (N x d x d), and the 3 x 3 Cauchy stress (N x 9): the law's
  /// at u from its committed states (PointwiseLaw::cauchy), nothing kept.
  void gradient(const double* u, double* H) const;
  /// grad u (N x d x d) at the u of the last internal_force or energy call, kept from it:
  /// what a caller that evaluated the force at u reads instead of another product with G.
  const double* last_gradient() const { return H_.data(); }
  void stress3(const double* u, std::vector<double>& sigma) const;

  /// The pointwise law between G and G^T, and the history it keeps.
  PointwiseLaw& law() { return *law_; }
  const PointwiseLaw& law() const { return *law_; }
  /// The Drucker-Prager points, the law itself or the one a FiniteRotationLaw wraps, or
  /// nullptr (for tests and diagnostics: the load path goes through history()).
  PlasticPoints* plastic();
  const PlasticPoints* plastic() const;
  /// A law with history: evaluates every particle at u and commits (nothing otherwise).
  void commit(const double* u) override;
  /// The law's tangents at u (PointwiseLaw::tangents), used by visit_tangent_rows until the
  /// next call (the Newton path calls it before each assembly); before the first call the
  /// rows use the elastic moduli of the material.
  void prepare_tangent(const double* u) override;

  /// Breaks the bonds (i, j) in both directions (irreversibly) and refreshes the rows of G
  /// and S they touch, so that force, energy and tangent rows are those of a model built
  /// without them (tests/models/test_bond_breaks.cpp). A particle whose live family no longer
  /// spans R^d is detached (NonlocalOperator::detach_quality). The surface band of the
  /// improved and strong formulations stays that of the intact body. Throws
  /// std::out_of_range for a particle index beyond the cloud, std::invalid_argument for a pair
  /// that is not a bond (neither (i, j) nor (j, i) in the families, or i == j; a bond broken
  /// already is still one), and std::logic_error (before
  /// changing anything) for the consistent formulation (G~ comes from a global correction)
  /// and for a stabilization stored without the operator it came from (operator order 2 at
  /// the assembled level: stabilization_storage matrix_free keeps the fit and refreshes).
  BondBreaks break_bonds(const std::vector<std::pair<ParticleId, ParticleId>>& bonds);
  /// The same at a state u whose internal force f the caller holds (internal_force(u, f) the
  /// last force or energy evaluated): f becomes the changed model's force at u, and
  /// `released` the strain energy the breaks released there. Each refreshed row i owns a
  /// share of the energy, V_i psi(H_i) plus its stabilization row (hourglass_energy.hpp),
  /// and of the force, that share's derivative; nothing else changes. So with the classical
  /// formulation of operator order 1 and float64 weights (what fracture scenes run) the
  /// shares of the refreshed rows are subtracted before and added after: a breaking step
  /// costs its rows, not another force and two energies. Otherwise both are evaluated anew.
  /// last_gradient() stays grad u at u.
  BondBreaks break_bonds(const std::vector<std::pair<ParticleId, ParticleId>>& bonds, const double* u, double* f);
  /// Cuts bonds at build time (precracks): break_bonds, and the cuts are then the body as built,
  /// not break events of a run (BondGraph::settle_events; the VTK field break_event counts only
  /// the run's).
  BondBreaks cut_bonds(const std::vector<std::pair<ParticleId, ParticleId>>& bonds);

  /// From now on the bonds break_bonds breaks soften (cohesive_bonds.hpp) instead of
  /// vanishing: their pair forces join the force, the energy and the stiffness bound. The
  /// family sums are the live graph's now (after precracks, which cut_bonds refuses after
  /// this call). The whole model's tangent rows (visit_tangent_rows, after prepare_tangent) add
  /// their slopes at u (CohesiveBonds::tangent_row); the listed rows' variant throws
  /// std::logic_error once a bond softens. A whole model only (not after limit_rows).
  void soften_broken_bonds(const CohesiveLaw& law);
  /// The softening bonds, or nullptr.
  CohesiveBonds* cohesive() { return cohesive_.get(); }
  const CohesiveBonds* cohesive() const { return cohesive_.get(); }

  const NonlocalOperator& G() const { return G_; }
  /// 1 or 2: the order of the fit G comes from (CorrespondenceOptions::operator_order).
  int operator_order() const { return order_; }
  /// S at its assembly level, or nullptr when C_hg = 0. With operator order 2, or the
  /// consistent formulation, S is stored assembled without the operator it came from.
  const StabilizationTerm* stabilization() const { return S_.get(); }
  const LinearElastic& material() const { return material_; }
  const std::vector<double>& volume() const { return volume_; }
  Formulation formulation() const { return formulation_; }
  /// Surface data (empty for the classical and consistent formulations).
  const Surface& surface() const { return surface_; }
  /// The consistent formulation: the trace on the boundary facets (from the uncorrected G, as
  /// the boundary measure was), for work-consistent loads; empty otherwise.
  const BoundaryTrace& trace() const { return trace_; }
  /// The consistent formulation: how the correction of G went.
  const ConsistencyReport& consistency() const { return consistency_; }

  // What drivers and the load path ask of any model (correspondence_output.cpp): the fields
  // displacement, stress, von_mises, mean_stress, volume; surface_stress and
  // surface_von_mises with boundary facets; subregion_E and surface for the improved and
  // strong formulations; the law's fields other than stress (PointwiseLaw::fields: with
  // plasticity eq_plastic_strain, plastic_strain, yielded, lbc_flagged);
  // for probes displacement_gradient and equivalent_strain, and stress_gradient.
  ModelHistory* history() override { return law_->history() ? this : nullptr; }
  bool turns_with_body() const override { return rotating_; }
  std::vector<OutputField> output_fields(const double* u, bool probe_fields = false,
                                         bool gradients = false) const override;
  std::vector<double> stress_measure(const double* u) const override;
  std::vector<PlanLine> plan() const override;
  std::vector<std::string> not_assembled() const override;

  // ModelHistory, through the law's LawHistory (only for a law with one: history() is
  // nullptr otherwise). commit(u) is the one above.
  void set_history_mode(HistoryMode mode) override;
  void commit_trial() override;
  void begin_step() override;
  std::size_t flag_violations(double tolerance) override;
  std::vector<double> history_variable() const override;
  std::size_t values_per_particle() const override;
  HistoryState save_history() const override;
  void restore_history(const HistoryState& state) override;
  void reset_history() override;

 private:
  double c_hg_ = 0.0;       // the stabilization coefficient asked for (for the plan)
  bool secant_ = false;     // CorrespondenceOptions::secant_stabilization
  /// The stabilization's centre factors from the committed states (secant_stabilization).
  void follow_secant_stiffness();
  double modulus_ = 0.0;    // C_hg 2 mu: c_i = modulus / tr K_i
  bool fracture_fields_ = false;  // CorrespondenceOptions::fracture_fields
  std::vector<double> x_;   // the particles' positions (surface stress at the facets)
  int dim_;
  int order_;
  bool rotating_ = false;  // finite_rotation: the tangent's blocks turn with the body
  Formulation formulation_;
  LinearElastic material_;
  Surface surface_;
  std::vector<double> volume_;
  std::shared_ptr<BondGraph> graph_;  // G's bond graph, which break_bonds changes
  NonlocalOperator G_;
  std::unique_ptr<StabilizationTerm> S_;
  std::vector<double> H_, Q_, P_;  // workspaces: grad u, V . P, and P for strong rows
  std::vector<double> Su_;         // S u (the energy; the band's G^T(-B) for strong rows)
  std::unique_ptr<PointwiseLaw> law_;
  std::vector<double> C_;             // the law's tangents at the last prepare_tangent
  std::size_t C_stride_ = 0;          // between particles in C_ (0: one for all)
  BoundaryTrace trace_;
  ConsistencyReport consistency_;
  std::optional<FollowerPressure> follower_;
  std::vector<double> follower_tangent_;  // its local rows at the last prepare_tangent
  std::unique_ptr<CohesiveBonds> cohesive_;  // soften_broken_bonds
  /// visit_tangent_rows(rows)' refusal once a bond softens.
  void check_tangent_rows() const;
  /// Replaces G by G~ (consistent_gradient.hpp) after keeping the trace of the facets.
  void make_consistent(const PointCloud& cloud, const Families& families, const BondWeights& weights,
                       BoundaryFacets& facets, WeightPrecision precision, const CorrectionShare* ranks);
  /// Row i's share of the strain energy at u, with f += sign its derivative (H_ row i set
  /// from G first): the row update of break_bonds (correspondence_breaks.cpp).
  double row_share(std::size_t i, const double* u, double sign, double* f);
  /// break_bonds' exceptions, thrown before anything changes.
  void check_breakable(const std::vector<std::pair<ParticleId, ParticleId>>& bonds) const;
  void visit_rows(const PointwiseTangent& C,
                  const std::function<void(std::size_t, const std::vector<ParticleId>&,
                                           const std::vector<double>&)>& visit,
                  const double* local = nullptr) const;
};

}  // namespace perinom

#pragma once
/// @file What a solver and the output need from the physics: residual pieces, energy, a
/// stiffness bound, the named fields a snapshot or probe reads, and the lines of a plan.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace perinom {

struct Loading;
class ModelHistory;

/// A named per-particle field: `components` values per particle, particle-major
/// (values.size() == particles() * components). Names are the VTK arrays' and CSV columns'.
struct OutputField {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

/// One line of `perinom check`'s plan: a label (padded to a column) and its text.
struct PlanLine {
  std::string label, text;
};

/// A discrete model with dofs_per_particle() unknowns per particle, stored point-major.
/// Solvers own the time loop; models only evaluate. Workspaces are allocated once, so
/// internal_force() never allocates.
class Model {
 public:
  virtual ~Model() = default;
  virtual std::size_t particles() const = 0;
  virtual int dofs_per_particle() const = 0;
  std::size_t dofs() const { return particles() * dofs_per_particle(); }

  /// f = dW/du, the internal force (N) at displacement u (m).
  virtual void internal_force(const double* u, double* f) = 0;
  /// W(u), the stored energy (J), stabilization included.
  virtual double energy(const double* u) = 0;
  /// Lumped mass per degree of freedom (kg).
  virtual std::vector<double> lumped_mass() const = 0;
  /// sum_j |K_ij| per degree of freedom (N/m), K the stiffness at the reference state.
  virtual std::vector<double> stiffness_row_sums() const = 0;
  /// Bytes held by the assembled operators, by name (for `perinom check`).
  virtual std::vector<std::pair<std::string, std::size_t>> memory() const = 0;
  /// Solvers call this before evaluating forces under `loading` at factor s, for loads the
  /// model itself carries (follower pressures); most models carry none.
  virtual void follow_loads(const Loading& loading, double s) { (void)loading, (void)s; }

  /// The solvers' reductions for a model spread over MPI ranks (distributed/distributed_model.hpp):
  /// `values` holds this process's partial sums (maxima), over its own particles, and receives
  /// the totals over all ranks. A model on one process has nothing to add.
  virtual void sum_across_ranks(double* values, int count) const { (void)values, (void)count; }
  virtual void max_across_ranks(double* values, int count) const { (void)values, (void)count; }

  /// The path-dependent state a load path commits (model_history.hpp), or nullptr for a
  /// model whose answer depends on u alone (elastic).
  virtual ModelHistory* history() { return nullptr; }
  const ModelHistory* history() const { return const_cast<Model*>(this)->history(); }
  /// Whether the stiffness changes with u before anything yields (finite rotation: the stress
  /// and follower loads turn with the body), so that a tangent can turn singular at a limit or
  /// bifurcation point of an elastic state; false for small strain, where only yielding can.
  virtual bool turns_with_body() const { return false; }

  /// The fields a snapshot writes at u, in order (VTK point data, CSV columns). `probe_fields`
  /// adds those only probes read (e.g. the displacement gradient); with `gradients` also the
  /// fields' nonlocal gradients a reconstructing point probe needs.
  /// A model written only for a solver (a test's) has no output: the default throws.
  virtual std::vector<OutputField> output_fields(const double* u, bool probe_fields = false,
                                                 bool gradients = false) const {
    (void)u, (void)probe_fields, (void)gradients;
    throw std::logic_error("this model offers no output fields");
  }
  /// The model's stress measure at u, as the Newton check compares two answers (a solid's
  /// 3 x 3 Cauchy stress, N x 9, Pa; a plate's moments, N x 3, N m / m).
  virtual std::vector<double> stress_measure(const double* u) const {
    (void)u;
    throw std::logic_error("this model offers no stress measure");
  }
  /// The model's lines of `perinom check`'s plan (its kind and options, what its build found);
  /// a line labelled "dimension" completes the plan's dimension line (", plane strain").
  virtual std::vector<PlanLine> plan() const { return {}; }
  /// What the model does not assemble: the items of the plan's "not assembled:" line.
  virtual std::vector<std::string> not_assembled() const { return {}; }
  /// What stops the body's rigid motions, in the scene's words: the end of the error for a
  /// singular elastic stiffness (a missing support). A solid fixes components.
  virtual std::string support_advice() const {
    return "fix enough components to stop rigid translation and rotation";
  }
};

}  // namespace perinom

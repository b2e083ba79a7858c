#pragma once
/// @file A model spread over MPI ranks (issue 19): this rank's owned particles as a Model the
/// serial solvers run unchanged. Its dofs are the owned particles' (in curve order); a force
/// evaluation copies them into the local part's array, fills the ghosts from their owners
/// (Halo) and evaluates the local model, whose rows are limited to the owned ones
/// (LocalModel::limit_rows: a correspondence model or a thin plate). The solvers' sums go
/// over the ranks. A law with
/// history (plasticity) is driven through it as a ModelHistory over the ranks
/// (distributed_history.cpp). Its stiffness rows are the owned particles', their columns the
/// local part's particles (owned, then ghosts): what Newton over the ranks assembles.
#include <memory>
#include <vector>

#include "perinom/distributed/ranks.hpp"
#include "perinom/models/local_model.hpp"
#include "perinom/models/model_history.hpp"
#include "perinom/neighbors/local_part.hpp"

namespace perinom {

class DistributedModel : public TangentModel, public ModelHistory {
 public:
  /// `local` is the model of `part`'s particles (owned first, then the ghosts), built on
  /// subcloud(cloud, part.particles); its rows are limited here. Both must outlive this.
  DistributedModel(LocalModel& local, const LocalPart& part);

  std::size_t particles() const override { return part_.owned; }
  int dofs_per_particle() const override { return local_.dofs_per_particle(); }
  void internal_force(const double* u, double* f) override;
  double energy(const double* u) override;  ///< this rank's share (the solvers sum it)
  std::vector<double> lumped_mass() const override;
  std::vector<double> stiffness_row_sums() const override;
  std::vector<std::pair<std::string, std::size_t>> memory() const override;
  /// The local model's fields at the owned particles.
  std::vector<OutputField> output_fields(const double* u, bool probe_fields = false,
                                         bool gradients = false) const override;
  std::vector<double> stress_measure(const double* u) const override;  ///< the owned particles'
  std::string support_advice() const override { return local_.support_advice(); }
  void sum_across_ranks(double* values, int count) const override { sum_over_ranks(values, count); }
  void max_across_ranks(double* values, int count) const override { max_over_ranks(values, count); }

  /// The local part's array (owned, then ghosts) at the owned values u, ghosts exchanged:
  /// what the local model evaluates (for output and probes through it).
  const std::vector<double>& local_state(const double* u) const;

  // TangentModel over the ranks: the local model's tangent at the local state (collective).
  void prepare_tangent(const double* u) override { local_.prepare_tangent(local_state(u).data()); }
  void visit_tangent_rows(const TangentRowVisitor& visit) const override;  ///< the owned rows
  std::size_t column_particles() const override { return part_.particles.size(); }
  std::vector<double> column_values(const double* own) const override { return local_state(own); }

  /// Itself when the local model has history (a plastic law), else nullptr.
  ModelHistory* history() override { return local_.history() ? this : nullptr; }
  bool turns_with_body() const override { return local_.turns_with_body(); }
  // ModelHistory over the ranks: the local model's, whose near ghosts evaluate the same
  // states as their owners (their families are whole) but in another order, so after every
  // commit and flagging each ghost takes its owner's committed state and flag (the same bits
  // on every rank); counts, flags and xi are the owned particles'.
  void set_history_mode(HistoryMode mode) override;
  /// The owned particles newly flagged, summed over the ranks (every rank sees the total).
  std::size_t flag_violations(double tolerance) override;
  std::vector<double> history_variable() const override;  ///< the owned particles'
  std::size_t values_per_particle() const override;
  HistoryState save_history() const override;              ///< the owned particles'
  void restore_history(const HistoryState& state) override;  ///< the owned particles'
  void reset_history() override;
  void commit(const double* u) override;
  void commit_trial() override;
  void begin_step() override;

 private:
  LocalModel& local_;
  ModelHistory& local_history() const;  ///< the local model's (std::logic_error when it has none)
  const LocalPart& part_;
  std::vector<ParticleId> owned_rows() const;  ///< 0 .. owned - 1
  mutable std::vector<double> u_local_;  // the halo's array: it must not move
  std::vector<double> f_local_;
  std::unique_ptr<Halo> halo_;
  /// The owners' committed states and flags to their ghosts (local history to share_ first).
  void share_history(HistoryState state);
  std::vector<double> shared_;  // the history halo's array: per local particle, its values and flag
  std::unique_ptr<Halo> history_halo_;
};

}  // namespace perinom

#pragma once
/// @file What a distributed rank needs of the model of its local part (issue 19): rows that
/// can be limited to the owned ones, and the stiffness of listed rows. DistributedModel runs
/// any such model over the ranks (the correspondence model, the thin plate).
#include <cstddef>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/models/tangent_model.hpp"

namespace perinom {

/// The model of a rank's local part: its particles are the owned ones first, then the near
/// ghosts (within one horizon of an owned one: their rows are whole), then the far ghosts
/// (they only lend their values).
class LocalModel : public TangentModel {
 public:
  using TangentModel::visit_tangent_rows;
  using Model::stiffness_row_sums;
  /// internal_force evaluates the rows of the first `evaluated` particles (owned and near)
  /// and writes the force of the first `written` (owned), and energy() sums the written
  /// particles' share; only those rows are then meaningful. std::logic_error for a model
  /// whose rows read the whole body.
  virtual void limit_rows(std::size_t evaluated, std::size_t written) = 0;
  /// The stiffness row sums (sum_j |K_ij| per dof) of the listed particles (sorted, distinct).
  virtual std::vector<double> stiffness_row_sums(const std::vector<ParticleId>& rows) const = 0;
  /// The listed particles' tangent rows (sorted, distinct; their columns sorted), at the last
  /// prepare_tangent.
  virtual void visit_tangent_rows(const std::vector<ParticleId>& rows, const TangentRowVisitor& visit) const = 0;
};

}  // namespace perinom

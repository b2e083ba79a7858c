#pragma once
/// @file What the Newton path needs from a model: the stiffness dF/du as block rows.
#include <cstddef>
#include <functional>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/models/model.hpp"
#include "perinom/operators/row_accumulator.hpp"

namespace perinom {

/// visit(i, cols, blocks): the d rows of particle i (d = dofs_per_particle()); cols the
/// particles the rows couple to, sorted; blocks the d x d block of each column, row-major
/// per column (blocks[(q d + a) d + b] = dF_{i a} / du_{cols[q] b}).
/// (for_each_block_row visits rows the same way.)
using TangentRowVisitor = BlockRowVisitor;

/// A model whose stiffness K = dF/du can be visited row by row (StaticSystem assembles the
/// Jacobian from these rows). visit_tangent_rows may call visit concurrently for distinct
/// particles. A tangent that depends on u (plasticity) is evaluated by prepare_tangent(u)
/// before each visit; for a tangent that does not depend on u (linear models) it does nothing.
class TangentModel : public Model {
 public:
  virtual void visit_tangent_rows(const TangentRowVisitor& visit) const = 0;
  virtual void prepare_tangent(const double* u) = 0;
  /// The particles the visited rows' columns number: particles() for a whole model. A part
  /// of a model spread over MPI ranks (DistributedModel) visits its own particles' rows, and
  /// its columns number its own particles, then the ghosts its rows reach.
  virtual std::size_t column_particles() const { return particles(); }
  /// Values given per dof of the own particles, over the column particles' dofs: a ghost's
  /// values are its owner's (collective over the ranks). A whole model's are `own` itself.
  virtual std::vector<double> column_values(const double* own) const { return {own, own + dofs()}; }
};

}  // namespace perinom

#pragma once
/// @file Whether a Jacobian holds a rigid motion at zero force (a singular stiffness the
/// supports leave free), for GAMG's Newton: conjugate gradients on such a matrix may converge
/// (the loads orthogonal to the motion: serially, a bar free along y was "converged" with an
/// arbitrary y translation) or stop as indefinite (over 2 ranks), by rounding. Internal to the
/// PETSc module (lib/solvers).
#include <petscmat.h>

namespace perinom::detail {

/// How J meets its near-null space Q (orthonormal: GAMG's rigid-body modes in reduced
/// coordinates, set_near_null_space): the smallest and largest singular values of J Q over
/// ||J||_inf. A held mode's force lies at the held dofs' neighbours, so both fall as the body
/// grows (about N^-1/2 on a pinned plate): a combination of rigid motions is free when the
/// smallest is far below the largest (the Gram matrix resolves it to sqrt(eps) of the largest),
/// or all are when the largest is rounding. +infinity for both when J has no near-null space.
/// Collective.
struct RigidNull {
  double smallest, largest;
  /// A free combination: the weakest below 1e-6 of the strongest, or the strongest rounding.
  bool free() const { return smallest < 1e-6 * largest || largest < 1e-12; }
};
RigidNull rigid_null_measure(Mat J);

}  // namespace perinom::detail

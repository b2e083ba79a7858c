#pragma once
/// @file Whether a Jacobian holds a rigid motion at zero force (a singular stiffness the
/// supports leave free), for GAMG's Newton: conjugate gradients on such a matrix may converge
/// (the loads orthogonal to the motion: serially, a bar free along y was "converged" with an
/// arbitrary y translation) or stop as indefinite (over 2 ranks), by rounding. Internal to the
/// PETSc module (lib/solvers).
#include <petscmat.h>

namespace perinom::detail {

/// sigma_min(J Q) / ||J||_inf over J's near-null space Q (orthonormal: GAMG's rigid-body
/// modes in reduced coordinates, set_near_null_space): about 1e-16 when a combination of
/// rigid motions is free, far above 1e-10 when the supports hold them all (the force they
/// leave at the held dofs' neighbours). +infinity when J has no near-null space. Collective.
double rigid_null_measure(Mat J);

}  // namespace perinom::detail

#pragma once
/// @file The Galerkin reduction of a static problem to its free degrees of freedom, shared by
/// the stability check (spectrum.cpp) and the direct solver (direct.cpp). Internal to
/// lib/solvers: Eigen stays out of the public headers.
#include <Eigen/SparseCore>

#include <cstdint>
#include <vector>

#include "perinom/models/loading.hpp"
#include "perinom/models/tangent_model.hpp"

namespace perinom::detail {

using Sparse = Eigen::SparseMatrix<double>;

/// -1 for a constrained dof, else its index among the free ones.
std::vector<std::int64_t> free_index(std::size_t dofs, const Loading& loading);

/// K = dF/du from the model's block rows at its last prepare_tangent.
Sparse assemble_stiffness(const TangentModel& model);

/// u = T u_R + u_p: T is the identity on the free dofs, zero rows for dofs fixed on their
/// particle, and (I - A_FF)^-1 A_FR for face-located constraints (u_F = scale (t - sum coef
/// u_c), A from the couplings); u_p holds what the targets t at load factor s prescribe with
/// u_R = 0. Throws InputError when I - A_FF is singular.
struct Reduction {
  Sparse T;
  std::vector<double> prescribed;
};
Reduction reduce(std::size_t dofs, const Loading& loading, const std::vector<std::int64_t>& index, int n_free,
                 double s = 0.0);

}  // namespace perinom::detail

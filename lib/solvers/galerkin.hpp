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

/// T by rows: a free dof is its own column (index[g] >= 0), a constrained one is T's row of
/// it (fixed[g]: (column, value) pairs; empty for a dof fixed on its particle).
struct TRows {
  TRows(const Sparse& T, const std::vector<std::int64_t>& free_index);
  std::vector<std::int64_t> index;
  std::vector<std::vector<std::pair<int, double>>> fixed;
  int columns = 0;
};

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

/// K_T = T^T K T (K from the model's tangent rows at its last prepare_tangent), rows sorted,
/// assembled from the rows in parallel: the same matrix as Sparse(T^T K T) without forming
/// K (3.5-3.7 s against about 12 s on the 2-D plate at 101k particles, 2 threads). Throws
/// InputError past 2^31 - 1 nonzeros (its indices, and PETSc's here, are 32-bit).
RowSparse reduced_stiffness(const TangentModel& model, const TRows& t);

/// K_T's rows for a model spread over MPI ranks whose constraints all sit on their particles
/// (T only selects the free dofs): one row per own free dof (free_index over the own dofs,
/// -1 for a constrained one), its columns the global free numbers `column` gives each column
/// dof (TangentModel::column_values; -1 for a constrained dof) out of `columns`, sorted.
RowSparse own_stiffness(const TangentModel& model, const std::vector<std::int64_t>& free_index,
                        const std::vector<int>& column, int columns);

}  // namespace perinom::detail

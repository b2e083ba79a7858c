// Newton's static problem for PETSc SNES: the reduced form, and over ranks the multiplier
// form of face-located constraints (petsc_reduced.hpp).
#include "petsc_reduced.hpp"

#include <numeric>

#include "perinom/core/error.hpp"
#include "petsc_session.hpp"

namespace perinom::detail {

Reduced::Reduced(TangentModel& m, const Loading& l) : model(m), loading(l) {
  int size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  spread = size > 1;
  const std::size_t n = model.dofs();
  const bool multiplied = spread && any_couplings();
  std::vector<std::int64_t> index(n);
  if (multiplied) std::iota(index.begin(), index.end(), std::int64_t(0));
  else index = free_index(n, loading);
  int free = 0;
  for (const auto k : index) free += k >= 0 ? 1 : 0;
  if (multiplied) {
    // u is x's first part: T the identity, nothing prescribed.
    T = Sparse(Eigen::Index(n), Eigen::Index(n));
    T.setIdentity();
    p0 = dp = Eigen::VectorXd::Zero(Eigen::Index(n));
    lambdas = PetscInt(loading.fixed.size());
  } else {
    Reduction at0 = reduce(n, loading, index, free, 0.0);
    const Reduction at1 = reduce(n, loading, index, free, 1.0);
    T = std::move(at0.T);
    p0 = Eigen::Map<const Eigen::VectorXd>(at0.prescribed.data(), static_cast<Eigen::Index>(n));
    dp = Eigen::Map<const Eigen::VectorXd>(at1.prescribed.data(), static_cast<Eigen::Index>(n)) - p0;
  }
  rows = std::make_unique<TRows>(T, index);
  u.resize(static_cast<Eigen::Index>(n));
  f.resize(static_cast<Eigen::Index>(n));
  if (spread) number_columns(index, free + lambdas);
  if (multiplied) constraint_rows();
}

bool Reduced::any_couplings() const {
  int couplings = loading.coupled_constraints() ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &couplings, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  return couplings != 0;
}

void Reduced::constraint_rows() {
  const PetscInt own = PetscInt(model.dofs());
  const std::vector<double> sums = model.stiffness_row_sums();
  double mean[2] = {std::accumulate(sums.begin(), sums.end(), 0.0), double(sums.size())};
  model.sum_across_ranks(mean, 2);
  k_E = mean[0] / mean[1];
  auto add = [&](PetscInt k, PetscInt dof, double v) {
    v *= k_E;
    e_row.push_back(first + own + k), e_col.push_back(dof), e_value.push_back(v);  // E
    e_row.push_back(dof), e_col.push_back(first + own + k), e_value.push_back(v);  // E^T
  };
  for (PetscInt k = 0; k < lambdas; ++k) {
    add(k, first + PetscInt(loading.fixed[std::size_t(k)]), 1.0 / loading.scale[std::size_t(k)]);
    for (Offset c = loading.couplings[std::size_t(k)]; c < loading.couplings[std::size_t(k) + 1]; ++c)
      add(k, column[std::size_t(loading.coupled[c])], loading.coef[c]);
  }
  check(MatCreate(PETSC_COMM_WORLD, &E.p), "MatCreate");
  check(MatSetSizes(E.p, own + lambdas, own + lambdas, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(E.p, MATAIJ), "MatSetType");
  check(MatSetUp(E.p), "MatSetUp");
  check(MatSetOption(E.p, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
  check(add_constraints(E.p), "MatSetValues");
  check(MatAssemblyBegin(E.p, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(E.p, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

PetscErrorCode Reduced::add_constraints(Mat A) const {
  PetscErrorCode e = 0;
  for (std::size_t k = 0; k < e_row.size() && !e; ++k)
    e = MatSetValues(A, 1, &e_row[k], 1, &e_col[k], &e_value[k], ADD_VALUES);
  return e;
}

void Reduced::number_columns(const std::vector<std::int64_t>& index, PetscInt own) {
  MPI_Exscan(&own, &first, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) first = 0;  // MPI_Exscan leaves rank 0's undefined
  MPI_Allreduce(&own, &global, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  std::vector<double> number(index.size());
  for (std::size_t k = 0; k < index.size(); ++k) number[k] = index[k] >= 0 ? double(first + index[k]) : -1.0;
  const std::vector<double> at_columns = model.column_values(number.data());
  column.assign(at_columns.begin(), at_columns.end());
}

void Reduced::expand(const double* x) {
  u = T * Eigen::Map<const Eigen::VectorXd>(x, T.cols()) + p0 + s * dp;
}

void Reduced::force() {
  model.follow_loads(loading, s);
  model.internal_force(u.data(), f.data());
  if (loading.has_force())
    for (Eigen::Index k = 0; k < f.size(); ++k) f[k] -= loading.force_at(s, static_cast<std::size_t>(k));
}

void Reduced::residual(const double* x, double* R) {
  expand(x);
  force();
  Eigen::Map<Eigen::VectorXd>(R, T.cols()) = T.transpose() * f;
  for (PetscInt k = 0; k < lambdas; ++k) R[T.cols() + k] = -k_E * loading.target(s, std::size_t(k));
}

RowSparse Reduced::jacobian(const double* x) {
  expand(x);
  model.prepare_tangent(u.data());
  return spread ? own_stiffness(model, rows->index, column, global) : reduced_stiffness(model, *rows);
}

}  // namespace perinom::detail

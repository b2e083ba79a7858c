#include "petsc_rigid_null.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "petsc_session.hpp"

namespace perinom::detail {

double rigid_null_measure(Mat J) {
  MatNullSpace space = nullptr;
  check(MatGetNearNullSpace(J, &space), "MatGetNearNullSpace");
  if (!space) return std::numeric_limits<double>::infinity();
  PetscBool constant = PETSC_FALSE;
  PetscInt m = 0;
  const Vec* q = nullptr;
  check(MatNullSpaceGetVecs(space, &constant, &m, &q), "MatNullSpaceGetVecs");
  if (m == 0) return std::numeric_limits<double>::infinity();
  // The modes' values through J's own vectors: serially they were made before J's layout
  // was set up (global size -1), and MatMult refuses them.
  Vec x = nullptr;
  check(MatCreateVecs(J, &x, nullptr), "MatCreateVecs");
  std::vector<Vec> w(std::size_t(m), nullptr);
  for (PetscInt a = 0; a < m; ++a) {
    const PetscScalar* from = nullptr;
    PetscScalar* to = nullptr;
    PetscInt n = 0;
    check(VecGetLocalSize(q[a], &n), "VecGetLocalSize");
    check(VecGetArrayRead(q[a], &from), "VecGetArrayRead");
    check(VecGetArray(x, &to), "VecGetArray");
    std::copy(from, from + n, to);
    check(VecRestoreArray(x, &to), "VecRestoreArray");
    check(VecRestoreArrayRead(q[a], &from), "VecRestoreArrayRead");
    check(MatCreateVecs(J, nullptr, &w[std::size_t(a)]), "MatCreateVecs");
    check(MatMult(J, x, w[std::size_t(a)]), "MatMult");
  }
  VecDestroy(&x);
  // The Gram matrix of J Q: its smallest eigenvalue is sigma_min(J Q)^2 (Q orthonormal).
  Eigen::MatrixXd gram(m, m);
  for (PetscInt a = 0; a < m; ++a)
    for (PetscInt b = 0; b <= a; ++b) {
      PetscScalar dot = 0.0;
      check(VecDot(w[std::size_t(a)], w[std::size_t(b)], &dot), "VecDot");
      gram(a, b) = gram(b, a) = dot;
    }
  for (Vec& v : w) VecDestroy(&v);
  PetscReal scale = 0.0;
  check(MatNorm(J, NORM_INFINITY, &scale), "MatNorm");
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram, Eigen::EigenvaluesOnly).eigenvalues()(0);
  return scale > 0.0 ? std::sqrt(std::max(smallest, 0.0)) / scale : std::numeric_limits<double>::infinity();
}

}  // namespace perinom::detail

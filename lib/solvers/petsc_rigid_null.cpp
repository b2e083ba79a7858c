#include "petsc_rigid_null.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "petsc_session.hpp"

namespace perinom::detail {

RigidNull rigid_null_measure(Mat J) {
  constexpr double none = std::numeric_limits<double>::infinity();
  MatNullSpace space = nullptr;
  check(MatGetNearNullSpace(J, &space), "MatGetNearNullSpace");
  if (!space) return {none, none};
  PetscBool constant = PETSC_FALSE;
  PetscInt m = 0;
  const Vec* q = nullptr;
  check(MatNullSpaceGetVecs(space, &constant, &m, &q), "MatNullSpaceGetVecs");
  if (m == 0) return {none, none};
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
  const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram, Eigen::EigenvaluesOnly).eigenvalues();
  if (!(scale > 0.0)) return {none, none};
  return {std::sqrt(std::max(lambda(0), 0.0)) / scale, std::sqrt(std::max(lambda(m - 1), 0.0)) / scale};
}

}  // namespace perinom::detail

#include "perinom/solvers/spectrum.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>

#include "perinom/core/error.hpp"
#include "galerkin.hpp"
#include "inertia.hpp"

namespace perinom {

using detail::Sparse;

std::string SpectrumReport::verdict() const {
  char line[320];
  if (stable() && singular > 0) {
    std::snprintf(line, sizeof line,
                  "stable but singular: %zu zero eigenvalues (rigid motions the supports leave free, or a mechanism): "
                  "no static balance for a load along them",
                  singular);
    return line;
  }
  if (stable()) return "stable";
  std::snprintf(line, sizeof line,
                "UNSTABLE: %zu eigenvalues with negative real part and %zu complex, growth rate %.3e 1/s",
                negative, complex, growth_rate);
  return line;
}

std::size_t free_dofs(const TangentModel& model, const Loading& loading) {
  std::vector<char> fixed(model.dofs(), 0);
  for (const auto dof : loading.fixed) fixed[dof] = 1;
  return model.dofs() - static_cast<std::size_t>(std::count(fixed.begin(), fixed.end(), 1));
}

SpectrumReport stiffness_spectrum(TangentModel& model, const Loading& loading, const SpectrumOptions& options) {
  check_loading(loading, model.dofs());
  const auto start = std::chrono::steady_clock::now();
  SpectrumReport rep;
  const std::size_t n_all = model.dofs();
  rep.dofs = free_dofs(model, loading);
  const int n = static_cast<int>(rep.dofs);
  if (n == 0) return rep;

  // 1. The Galerkin reduction K_T = T^T K T, M_T = T^T M T, and K_T's symmetry defect.
  const std::vector<double> zero(n_all, 0.0);
  model.prepare_tangent(zero.data());
  const auto index = detail::free_index(n_all, loading);
  const Sparse T = detail::reduce(n_all, loading, index, n).T;
  const auto mass = model.lumped_mass();
  const Eigen::Map<const Eigen::VectorXd> m(mass.data(), static_cast<Eigen::Index>(n_all));
  const Sparse KT_sparse(detail::reduced_stiffness(model, detail::TRows(T, index)));
  const Sparse MT_sparse = Sparse(T.transpose() * m.asDiagonal() * T);
  const double k_norm = KT_sparse.norm();
  rep.symmetry_defect = k_norm > 0.0 ? Sparse(KT_sparse - Sparse(KT_sparse.transpose())).norm() / k_norm : 0.0;
  const auto finish = [&] {
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return rep;
  };

  // 2. Symmetric: the inertia of K_T (sparse LDL^T), no dense solve and no size limit.
  if (options.sparse_when_symmetric && rep.symmetry_defect <= options.symmetric_tolerance) {
    const PencilInertia in = pencil_inertia(KT_sparse, MT_sparse);
    rep.method = in.cholesky ? "sparse Cholesky: positive definite" : "sparse LDL^T inertia";
    rep.negative = static_cast<std::size_t>(in.negative);
    rep.singular = static_cast<std::size_t>(in.zero);
    rep.max_abs = in.max_lambda;
    rep.min_real = in.min_lambda;
    rep.growth_rate = in.negative > 0 ? std::sqrt(std::max(-in.min_lambda, 0.0)) : 0.0;
    return finish();
  }
  if (rep.dofs > options.max_dofs)
    throw InputError("stability check: " + std::to_string(rep.dofs) + " free degrees of freedom of a non-symmetric "
                     "stiffness (defect " + std::to_string(rep.symmetry_defect) + "), above the dense limit of " +
                     std::to_string(options.max_dofs) + " (coarsen discretization.dx to check the formulation)");
  Eigen::MatrixXd KT = Eigen::MatrixXd(KT_sparse);
  const Eigen::MatrixXd MT = Eigen::MatrixXd(MT_sparse);

  // 3. A = L^-1 K_T L^-T with M_T = L L^T (M_T is diagonal unless constraints are coupled).
  if (!loading.coupled_constraints()) {
    const Eigen::VectorXd s = MT.diagonal().cwiseSqrt().cwiseInverse();
    KT = s.asDiagonal() * KT * s.asDiagonal();
  } else {
    const Eigen::LLT<Eigen::MatrixXd> llt(MT);
    if (llt.info() != Eigen::Success) throw InputError("stability check: the reduced mass T^T M T is not positive definite");
    llt.matrixL().solveInPlace(KT);  // L^-1 K
    KT.transposeInPlace();
    llt.matrixL().solveInPlace(KT);  // L^-1 (L^-1 K)^T = L^-1 K^T L^-T = A^T
    KT.transposeInPlace();
  }

  // 4. All eigenvalues, summarized.
  const Eigen::EigenSolver<Eigen::MatrixXd> es(KT, false);
  if (es.info() != Eigen::Success) throw SolveError("stability check: the dense eigenvalue solve did not converge");
  const Eigen::VectorXcd lambda = es.eigenvalues();
  rep.method = "dense";
  rep.max_abs = lambda.cwiseAbs().maxCoeff();
  rep.min_real = lambda.real().minCoeff();
  double max_imag = 0.0;
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    const std::complex<double> l = lambda[k];
    max_imag = std::max(max_imag, std::abs(l.imag()));
    rep.negative += l.real() < -options.negative_tolerance * rep.max_abs;
    rep.complex += std::abs(l.imag()) > options.complex_tolerance * rep.max_abs;
    rep.growth_rate = std::max(rep.growth_rate, std::abs(std::sqrt(l).imag()));
  }
  rep.max_imag_relative = rep.max_abs > 0.0 ? max_imag / rep.max_abs : 0.0;
  return finish();
}

}  // namespace perinom

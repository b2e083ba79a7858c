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
#include "inertia.hpp"

namespace perinom {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

/// -1 for a constrained dof, else its index among the free ones.
std::vector<std::int64_t> free_index(std::size_t dofs, const Loading& loading) {
  std::vector<std::int64_t> index(dofs, 0);
  for (const auto dof : loading.fixed) index[dof] = -1;
  std::int64_t next = 0;
  for (auto& k : index) k = k < 0 ? -1 : next++;
  return index;
}

/// K = dF/du from the model's block rows (visit may run concurrently: each particle writes
/// only its own slot).
Sparse assemble_stiffness(const TangentModel& model) {
  const int d = model.dofs_per_particle();
  std::vector<Triplets> rows(model.particles());
  model.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
    auto& t = rows[i];
    t.clear();
    for (std::size_t q = 0; q < cols.size(); ++q)
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b)
          t.emplace_back(static_cast<int>(i * d + a), static_cast<int>(cols[q] * d + b), blocks[(q * d + a) * d + b]);
  });
  Triplets all;
  for (auto& t : rows) all.insert(all.end(), t.begin(), t.end()), Triplets().swap(t);
  const int n = static_cast<int>(model.dofs());
  Sparse K(n, n);
  K.setFromTriplets(all.begin(), all.end());
  return K;
}

/// T with u = T u_R: identity on the free dofs; zero rows for dofs fixed on their particle;
/// (I - A_FF)^-1 A_FR for face-located constraints (A from u_F = -scale sum coef u_c).
Sparse reduction(std::size_t dofs, const Loading& loading, const std::vector<std::int64_t>& index, int n_free) {
  Triplets t;
  for (std::size_t g = 0; g < dofs; ++g)
    if (index[g] >= 0) t.emplace_back(static_cast<int>(g), static_cast<int>(index[g]), 1.0);
  if (loading.coupled_constraints()) {
    const int nf = static_cast<int>(loading.fixed.size());
    std::vector<std::int64_t> constraint_of(dofs, -1);
    for (int k = 0; k < nf; ++k) constraint_of[loading.fixed[k]] = k;
    Triplets ff, fr;
    for (int k = 0; k < nf; ++k) {
      ff.emplace_back(k, k, 1.0);
      for (Offset c = loading.couplings[k]; c < loading.couplings[k + 1]; ++c) {
        const double a = -loading.scale[k] * loading.coef[c];
        const std::int64_t dof = loading.coupled[c];
        if (constraint_of[dof] >= 0) ff.emplace_back(k, static_cast<int>(constraint_of[dof]), -a);
        else fr.emplace_back(k, static_cast<int>(index[dof]), a);
      }
    }
    Sparse I_minus_AFF(nf, nf), AFR(nf, n_free);
    I_minus_AFF.setFromTriplets(ff.begin(), ff.end());
    AFR.setFromTriplets(fr.begin(), fr.end());
    Eigen::SparseLU<Sparse> lu(I_minus_AFF);
    if (lu.info() != Eigen::Success)
      throw InputError("stability check: the face-located constraints are singular (I - A_FF has no inverse)");
    const Eigen::MatrixXd X = lu.solve(Eigen::MatrixXd(AFR));
    for (int k = 0; k < nf; ++k)
      for (int r = 0; r < n_free; ++r)
        if (X(k, r) != 0.0) t.emplace_back(static_cast<int>(loading.fixed[k]), r, X(k, r));
  }
  Sparse T(static_cast<int>(dofs), n_free);
  T.setFromTriplets(t.begin(), t.end());
  return T;
}

}  // namespace

std::string SpectrumReport::verdict() const {
  if (stable()) return "stable";
  char line[256];
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
  const auto start = std::chrono::steady_clock::now();
  SpectrumReport rep;
  const std::size_t n_all = model.dofs();
  rep.dofs = free_dofs(model, loading);
  const int n = static_cast<int>(rep.dofs);
  if (n == 0) return rep;

  // 1. The Galerkin reduction K_T = T^T K T, M_T = T^T M T, and K_T's symmetry defect.
  const std::vector<double> zero(n_all, 0.0);
  model.prepare_tangent(zero.data());
  const Sparse K = assemble_stiffness(model);
  const auto index = free_index(n_all, loading);
  const Sparse T = reduction(n_all, loading, index, n);
  const auto mass = model.lumped_mass();
  const Eigen::Map<const Eigen::VectorXd> m(mass.data(), static_cast<Eigen::Index>(n_all));
  const Sparse KT_sparse = Sparse(T.transpose() * K * T), MT_sparse = Sparse(T.transpose() * m.asDiagonal() * T);
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

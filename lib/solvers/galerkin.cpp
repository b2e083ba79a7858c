#include "galerkin.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseLU>

#include "perinom/core/error.hpp"

namespace perinom::detail {

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

Reduction reduce(std::size_t dofs, const Loading& loading, const std::vector<std::int64_t>& index, int n_free,
                 double s) {
  Reduction out;
  out.prescribed.assign(dofs, 0.0);
  Triplets t;
  const int nf = static_cast<int>(loading.fixed.size());
  if (!loading.coupled_constraints())
    for (int k = 0; k < nf; ++k) out.prescribed[loading.fixed[k]] = loading.target(s, k);
  for (std::size_t g = 0; g < dofs; ++g)
    if (index[g] >= 0) t.emplace_back(static_cast<int>(g), static_cast<int>(index[g]), 1.0);
  if (loading.coupled_constraints()) {
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
    // X = (I - A_FF)^-1 A_FR, sparse (Eigen solves it through dense panels of a few
    // columns): dense it would hold constraints x free dofs values (0.7 GB for the 2-D
    // plate at 100k particles).
    const Sparse X = lu.solve(AFR);
    Eigen::VectorXd st(nf);  // scale . t
    for (int k = 0; k < nf; ++k) st[k] = loading.scale[k] * loading.target(s, k);
    const Eigen::VectorXd uF = lu.solve(st);
    for (int k = 0; k < nf; ++k) out.prescribed[loading.fixed[k]] = uF[k];
    for (int r = 0; r < X.outerSize(); ++r)
      for (Sparse::InnerIterator it(X, r); it; ++it)
        if (it.value() != 0.0) t.emplace_back(static_cast<int>(loading.fixed[it.row()]), r, it.value());
  }
  out.T = Sparse(static_cast<int>(dofs), n_free);
  out.T.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace perinom::detail

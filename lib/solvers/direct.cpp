#include "perinom/solvers/direct.hpp"

#include <Eigen/CholmodSupport>

#include <cmath>
#include <cstdio>

#include "factor_memory.hpp"
#include "galerkin.hpp"
#include "perinom/core/error.hpp"
#include "perinom/core/memory.hpp"
#include "perinom/core/parallel.hpp"
#include "perinom/solvers/vector_ops.hpp"

namespace perinom {

using detail::Sparse;

SolveReport solve_direct(TangentModel& model, const Loading& loading, std::vector<double>& u,
                         const DirectOptions& options, Progress* progress) {
  check_loading(loading, model.dofs());
  if (model.history())
    throw InputError("solver.type: direct solves a linear problem; a model with history (plasticity) needs lbc, "
                     "adr or newton");
  if (loading.collocated)
    throw InputError("solver.type: direct needs constraints in Galerkin form (the improved and strong formulations "
                     "collocate theirs and are not symmetric); use newton or adr");
  const std::size_t n_all = model.dofs();
  const auto index = detail::free_index(n_all, loading);
  int n = 0;
  for (const auto k : index) n += k >= 0 ? 1 : 0;
  SolveReport rep;
  rep.iterations = 1;
  // The history's columns before anything can fail (a failed solve still writes its header).
  const int dpp = model.dofs_per_particle();
  rep.history.columns = {"residual"};
  for (const auto& c : loading.reaction_columns(dpp)) rep.history.columns.push_back(c);
  u.assign(n_all, 0.0);

  // K_T u_R = T^T (f - K u_p): K from the tangent rows, F(u_p) = K u_p from the model itself.
  if (progress) progress->phase("assembling the reduced stiffness");
  model.prepare_tangent(u.data());
  detail::Reduction red = detail::reduce(n_all, loading, index, n, 1.0);
  Eigen::VectorXd r(static_cast<Eigen::Index>(n_all));
  {
    std::vector<double> fp(n_all);
    model.internal_force(red.prescribed.data(), fp.data());
    for (std::size_t k = 0; k < n_all; ++k) r[static_cast<Eigen::Index>(k)] = loading.force_at(1.0, k) - fp[k];
  }
  const Eigen::VectorXd rhs = red.T.transpose() * r;
  const Sparse KT(detail::reduced_stiffness(model, detail::TRows(red.T, index)));
  // (The factor's analysed size is kept in the protected factor of Eigen's wrapper.)
  struct Llt : Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> {
    double values() const { return m_cholmodFactor ? double(m_cholmodFactor->xsize) : 0.0; }
  } llt;
  llt.cholmod().print = 0;
  llt.analyzePattern(KT);
  if (llt.info() == Eigen::Success) {
    const double values = llt.values();  // of the supernodes, their zeros included
    const double bytes = detail::predict_cholesky_bytes(double(KT.nonZeros()), values);
    if (progress) {
      char what[200];
      std::snprintf(what, sizeof what,
                    "direct: CHOLMOD's factor, predicted from its analysis: %.3g values in L, about %.0f MiB beside the "
                    "%.0f MiB the process holds",
                    values, bytes / 1048576.0, resident_bytes() / 1048576.0);
      progress->phase(what);
    }
    char subject[300];
    std::snprintf(subject, sizeof subject,
                  "solver.type: direct: CHOLMOD's Cholesky factor of K_T (%lld unknowns, %.3g entries; %.3g values in L)",
                  static_cast<long long>(KT.rows()), double(KT.nonZeros()), values);
    detail::require_factor_memory(bytes, subject,
                                  "use solver.type adr, or newton with solver.linear_solver gamg (PETSc's multigrid: "
                                  "no factors), or a larger discretization.dx",
                                  options.memory_limit);
  }
  if (progress) progress->phase("factoring K_T (CHOLMOD supernodal Cholesky)");
  llt.factorize(KT);
  if (llt.info() != Eigen::Success) {
    rep.failure = "the reduced stiffness K_T is not positive definite (a non-symmetric formulation, or a rigid mode "
                  "the constraints leave free)";
    if (progress) progress->finish();
    return rep;
  }
  // u = T u_R + u_p, checked by the model's own force reduced the same way; a residual above
  // the tolerance from the factor's rounding (a nearly incompressible body: K_T's condition
  // grows as lambda / mu) gets up to kRefinements steps of iterative refinement on the
  // same factor, each solving K_T du_R = T^T (f - F(u)).
  constexpr int kRefinements = 3;
  std::vector<double> fint(n_all);
  Eigen::VectorXd f(static_cast<Eigen::Index>(n_all)), res(static_cast<Eigen::Index>(n_all));
  for (std::size_t k = 0; k < n_all; ++k) f[static_cast<Eigen::Index>(k)] = loading.force_at(1.0, k);
  const double scale = std::max((red.T.transpose() * f).norm(), rhs.norm());
  Eigen::VectorXd step = llt.solve(rhs);
  for (int round = 0;; ++round) {
    const Eigen::VectorXd full = red.T * step;
    for (std::size_t k = 0; k < n_all; ++k) u[k] += full[static_cast<Eigen::Index>(k)] + (round == 0 ? red.prescribed[k] : 0.0);
    model.internal_force(u.data(), fint.data());
    for (std::size_t k = 0; k < n_all; ++k) res[static_cast<Eigen::Index>(k)] = f[static_cast<Eigen::Index>(k)] - fint[k];
    const Eigen::VectorXd reduced = red.T.transpose() * res;
    rep.residual = scale > 0.0 ? reduced.norm() / scale : reduced.norm();
    if (rep.residual <= options.tolerance || round == kRefinements || !std::isfinite(rep.residual)) break;
    step = llt.solve(reduced);
    rep.iterations = 2 + round;
  }
  // The guard of ADR and Newton: a displacement whose sum of squares is not finite (an entry
  // past about 1e154) is never kept. A plate 1e-100 m thick "converged" at w = 1.3e289 m.
  if (!std::isfinite(rep.residual) || !std::isfinite(norm(u))) {
    u.assign(n_all, 0.0);
    rep.iterations = 0;  // the last good state: the unloaded one
    rep.diverged = true;
    rep.diverged_at = 1;
    rep.failure = "direct: the displacement became NaN or Inf (its sum of squares overflows) in the solve; the last "
                  "good state is the unloaded one";
    if (progress) progress->finish();
    return rep;
  }
  // One history row, with the supports' reactions as Newton reports them.
  rep.history.add({rep.residual});
  if (loading.has_supports()) {
    std::vector<double> reactions(loading.support_names.size() * dpp);
    loading.reactions(fint.data(), 1.0, dpp, reactions.data());
    rep.history.values.insert(rep.history.values.end(), reactions.begin(), reactions.end());
  }
  rep.converged = rep.residual <= options.tolerance;
  if (!rep.converged) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "the direct solve's residual %.3e is above solver.tolerance %.1e", rep.residual,
                  options.tolerance);
    rep.failure = msg;
  }
  if (progress) {
    ProgressSample sample;
    sample.iteration = 1, sample.limit = 1, sample.residual = rep.residual, sample.target = options.tolerance;
    progress->update(sample);
    progress->finish();
  }
  return rep;
}

}  // namespace perinom

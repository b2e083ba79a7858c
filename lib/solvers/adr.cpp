#include "perinom/solvers/adr.hpp"

#include <cmath>

#include "perinom/core/error.hpp"
#include "perinom/solvers/vector_ops.hpp"

namespace perinom {
namespace {

void solve_adr_steps(Model& model, const Loading& loading, const AdrOptions& opt,
                             std::vector<double>& u, Progress* progress,
                             const Observer& observe, SolveReport& rep) {
  const std::size_t n = model.dofs();
  u.resize(n, 0.0);
  // The diagonal mass lambda = 1/4 sum_j |K_ij| (dt = 1), kept as its inverse.
  if (progress) progress->phase("summing the stiffness rows for the ADR mass");
  std::vector<double> inv_lambda = model.stiffness_row_sums();
  for (auto& l : inv_lambda) l = 4.0 / l;
  std::vector<double> v(n), f(n), f_old(n), fint(n), last_good(u);
  const double force_norm = loading.force.empty() ? 0.0 : norm(loading.force);
  const double* fext = loading.force.empty() ? nullptr : loading.force.data();
  rep.history.columns = {"iteration", "load_factor", "residual", "displacement_change",
                         "damping"};
  rep.history.reserve(opt.max_iterations / std::max<std::int64_t>(opt.history_every, 1) + 1);
  ProgressSample sample;
  sample.limit = opt.max_iterations;
  sample.load_steps = opt.load_steps;
  sample.target = opt.tolerance;

  // Residual force F = s f_ext - f_int on the free dofs; returns the relative residual.
  auto residual = [&](double s) {
    model.internal_force(u.data(), fint.data());
    double reaction2 = 0.0;
    for (const auto dof : loading.fixed) reaction2 += fint[dof] * fint[dof];
    parallel_for(n, [&](std::size_t k) { f[k] = (fext ? s * fext[k] : 0.0) - fint[k]; });
    loading.zero_fixed(f.data());
    const double fnorm = norm(f);
    if (!std::isfinite(fnorm)) {
      u = last_good;
      throw SolveError("ADR: the internal force became NaN or Inf at iteration " +
                       std::to_string(rep.iterations) + " (last finite state kept)");
    }
    const double load = std::max(s * force_norm, std::sqrt(reaction2));
    return load > 0.0 ? fnorm / load : fnorm;
  };

  for (int step = 1; step <= opt.load_steps; ++step) {
    const double s = static_cast<double>(step) / opt.load_steps;
    loading.impose(s, u.data());
    std::fill(v.begin(), v.end(), 0.0);
    double r = residual(s), du = 1.0, c = 0.0;
    bool first = true;
    rep.converged = false;
    sample.load_step = step;
    while (rep.iterations < opt.max_iterations) {
      // The seed's criterion (eq. 33) alone stops a solve that has barely moved; the
      // residual criterion makes sure it is in equilibrium.
      if (!first && r <= opt.tolerance && du <= opt.displacement_tolerance) {
        rep.converged = true;
        break;
      }
      if (first) {
        parallel_for(n, [&](std::size_t k) { v[k] = 0.5 * f[k] * inv_lambda[k]; });
      } else {
        // Damping from the local diagonal stiffness (Rayleigh quotient over u).
        const auto [num, den] = parallel_sums<2>(n, [&](std::size_t k, double* acc) {
          acc[1] += u[k] * u[k];
          if (v[k] != 0.0) acc[0] += u[k] * u[k] * (-(f[k] - f_old[k]) * inv_lambda[k] / v[k]);
        });
        c = (num > 0.0 && den > 0.0) ? 2.0 * std::sqrt(num / den) : 0.0;
        c = std::min(c, 1.999);
        const double keep = (2.0 - c) / (2.0 + c), push = 2.0 / (2.0 + c);
        parallel_for(n, [&](std::size_t k) { v[k] = keep * v[k] + push * f[k] * inv_lambda[k]; });
      }
      first = false;
      loading.zero_fixed(v.data());
      const double du2 = parallel_sums<1>(n, [&](std::size_t k, double* acc) {
        u[k] += v[k];
        acc[0] += v[k] * v[k];
      })[0];
      if (loading.coupled_constraints()) loading.impose(s, u.data());
      const double un = norm(u);
      du = un > 0.0 ? std::sqrt(du2) / un : std::sqrt(du2);
      f_old.swap(f);
      if (rep.iterations % 100 == 0) last_good = u;
      r = residual(s);
      ++rep.iterations;
      if (rep.iterations % opt.history_every == 0)
        rep.history.add({double(rep.iterations), s, r, du, c});
      observe(rep.iterations, s, u);
      if (progress && rep.iterations % 50 == 0) {
        sample.iteration = rep.iterations;
        sample.residual = r;
        progress->update(sample);
      }
    }
    rep.residual = r;
    rep.displacement_change = du;
    if (!rep.converged) break;
  }
  if (progress) progress->finish();
}

}  // namespace

SolveReport solve_adr(Model& model, const Loading& loading, const AdrOptions& opt,
                      std::vector<double>& u, Progress* progress, const Observer& observe) {
  SolveReport rep;
  try {
    solve_adr_steps(model, loading, opt, u, progress, observe, rep);
  } catch (const SolveError& e) {
    if (progress) progress->finish();
    rep.converged = false;
    rep.failure = e.what();
  }
  return rep;
}

}  // namespace perinom

#include "perinom/solvers/verlet.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "perinom/core/error.hpp"
#include "perinom/solvers/vector_ops.hpp"

namespace perinom {

double stable_time_step(const Model& model) {
  const auto rows = model.stiffness_row_sums();
  const auto mass = model.lumped_mass();
  double w2 = 0.0;
  for (std::size_t k = 0; k < rows.size(); ++k) w2 = std::max(w2, rows[k] / mass[k]);
  return 2.0 / std::sqrt(w2);
}

namespace {

void integrate(Model& model, const Loading& loading, const VerletOptions& opt,
               std::vector<double>& u, std::vector<double>& v, Progress* progress,
               const Observer& observe, SolveReport& rep) {
  const std::size_t n = model.dofs();
  u.resize(n, 0.0);
  v.resize(n, 0.0);
  if (progress) progress->phase("summing the stiffness rows for the stable time step");
  rep.stable_time_step = stable_time_step(model);
  const double dt = opt.dt > 0.0 ? opt.dt : opt.safety * rep.stable_time_step;
  auto inv_mass = model.lumped_mass();
  for (auto& m : inv_mass) m = 1.0 / m;
  const double* fext = loading.force.empty() ? nullptr : loading.force.data();
  // u_old, v_old: the state of the previous step, the last one that passed the guard.
  std::vector<double> a(n), fint(n), u_old(u), v_old(v);
  rep.history.columns = {"step", "time", "kinetic_energy", "strain_energy", "external_work",
                         "total_energy"};
  rep.history.reserve(opt.steps / std::max<std::int64_t>(opt.history_every, 1) + 2);
  auto factor = [&](double t) { return opt.ramp_time > 0.0 ? std::min(1.0, t / opt.ramp_time) : 1.0; };
  double work = 0.0;  // external work, trapezoidal in time
  auto diverged = [&](std::int64_t step, const std::string& what) {
    return DivergenceError("Verlet: " + what + " became NaN or Inf at step " + std::to_string(step), step);
  };
  // The guard, part 1: the acceleration (and so the internal force) is finite.
  auto accelerate = [&](std::int64_t step, double t) {
    model.internal_force(u.data(), fint.data());
    const double s = factor(t);
    const auto [a2, u2, v2] = parallel_sums<3>(n, [&](std::size_t k, double* acc) {
      a[k] = ((fext ? s * fext[k] : 0.0) - fint[k]) * inv_mass[k];
      acc[0] += a[k] * a[k], acc[1] += u[k] * u[k], acc[2] += v[k] * v[k];
    });
    loading.zero_fixed(a.data());
    if (!std::isfinite(a2 + u2 + v2)) throw diverged(step, "the internal force or the state");
  };
  // Part 2: the history row, checked before it is kept.
  auto energies = [&](std::int64_t step, double t) {
    const double kin = parallel_sums<1>(n, [&](std::size_t k, double* acc) {
      acc[0] += 0.5 * v[k] * v[k] / inv_mass[k];
    })[0];
    const double strain = model.energy(u.data());
    const std::array<double, 6> row{double(step), t, kin, strain, work, kin + strain - work};
    for (const double x : row)
      if (!std::isfinite(x)) throw diverged(step, "an energy");
    return row;
  };
  auto record = [&](const std::array<double, 6>& r) { rep.history.add({r[0], r[1], r[2], r[3], r[4], r[5]}); };
  double t = 0.0;
  loading.impose(factor(t), u.data());
  accelerate(0, t);
  record(energies(0, t));
  ProgressSample sample;
  sample.limit = opt.steps;
  for (std::int64_t step = 1; step <= opt.steps; ++step) {
    parallel_for(n, [&](std::size_t k) {
      v_old[k] = v[k];
      v[k] += 0.5 * dt * a[k];
      u_old[k] = u[k];
      u[k] += dt * v[k];
    });
    const double t_old = t;
    t += dt;
    try {
      loading.impose(factor(t), u.data());
      const double s_mid = 0.5 * (factor(t) + factor(t - dt));
      if (fext)
        work += s_mid * parallel_sums<1>(n, [&](std::size_t k, double* acc) { acc[0] += fext[k] * (u[k] - u_old[k]); })[0];
      accelerate(step, t);
      parallel_for(n, [&](std::size_t k) { v[k] += 0.5 * dt * a[k]; });
      loading.zero_fixed(v.data());
      const bool row = step % opt.history_every == 0;
      std::array<double, 6> r{};
      if (row) r = energies(step, t);
      observe(step, t, u);  // part 3: the snapshot writer refuses a non-finite field
      if (row) record(r);
    } catch (const SolveError& e) {
      u.swap(u_old), v.swap(v_old);
      rep.end_time = t_old;  // rep.iterations is still step - 1
      const auto* d = dynamic_cast<const DivergenceError*>(&e);
      throw DivergenceError(std::string(e.what()) + "; the last good state is step " + std::to_string(step - 1),
                            d ? d->step : step);
    }
    rep.iterations = step;
    rep.end_time = t;
    if (progress && step % 50 == 0) {
      sample.iteration = step;
      sample.time = t;
      progress->update(sample);
    }
  }
  rep.converged = true;
  if (progress) progress->finish();
}

}  // namespace

SolveReport solve_verlet(Model& model, const Loading& loading, const VerletOptions& opt,
                         std::vector<double>& u, std::vector<double>& v, Progress* progress,
                         const Observer& observe) {
  SolveReport rep;
  try {
    integrate(model, loading, opt, u, v, progress, observe, rep);
  } catch (const DivergenceError& e) {
    if (progress) progress->finish();
    rep.converged = false;
    rep.diverged = true;
    rep.diverged_at = e.step;
    rep.failure = e.what();
  } catch (const SolveError& e) {
    if (progress) progress->finish();
    rep.converged = false;
    rep.failure = e.what();
  }
  return rep;
}

}  // namespace perinom

#include "perinom/solvers/verlet.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "perinom/core/error.hpp"
#include "perinom/core/thread_governor.hpp"
#include "perinom/core/timer.hpp"
#include "perinom/solvers/vector_ops.hpp"

namespace perinom {

double stable_time_step(const Model& model) {
  const auto rows = model.stiffness_row_sums();
  const auto mass = model.lumped_mass();
  double w2 = 0.0;
  for (std::size_t k = 0; k < rows.size(); ++k) w2 = std::max(w2, rows[k] / mass[k]);
  model.max_across_ranks(&w2, 1);
  return 2.0 / std::sqrt(w2);
}

namespace {

/// The energy that rounding alone leaves in the strain energy and the constraints' work at a
/// state whose lumped masses m_k and displacements u_k give mu2 = sum_k m_k u_k^2 (kg m^2),
/// for a model whose stable step is `stable` (s). Both sum terms K_kj u_k u_j, each with a
/// relative error of eps, and sum_kj |K_kj| |u_k| |u_j| / 2 <= omega_max^2 mu2 / 2 (Gershgorin,
/// the stable step's own bound: omega_max = 2 / stable). A stress-free rigid motion's energies
/// are that rounding: a rotation held by its velocities gave 1.4e-12 J against 6e-11 J here, and
/// with no floor the guard stopped it as diverged. (The constraints' work sums the rounding of
/// their reactions times each step's motion: over a motion that moves one way, as a prescribed
/// velocity does, that too stays within the bound at the state reached.)
double rounding_energy(double stable, double mu2) {
  if (!std::isfinite(stable) || !(stable > 0.0)) return 0.0;  // no stiffness: no strain energy
  const double omega_max = 2.0 / stable;
  return std::numeric_limits<double>::epsilon() * 0.5 * omega_max * omega_max * mu2;
}

void integrate(Model& model, const Loading& loading, const VerletOptions& opt,
               std::vector<double>& u, std::vector<double>& v, Progress* progress,
               const Observer& observe, const Checkpoints<VerletState>& checkpoints,
               const VerletState* resume, const ModelChanges* changes, SolveReport& rep) {
  if (changes && resume && !(changes->save && changes->restore))
    throw std::invalid_argument("solve_verlet: a run whose model changes (broken bonds) is resumed only when they restore themselves");
  if (changes && resume && resume->changes.empty())
    throw std::invalid_argument("solve_verlet: the resumed state holds no record of the model's changes");
  if (changes && resume) changes->restore(resume->changes);
  const std::size_t n = model.dofs();
  u.resize(n, 0.0);
  v.resize(n, 0.0);
  if (progress && !(changes && resume)) progress->phase("summing the stiffness rows for the stable time step");
  // The changes keep the row sums they follow: the same step, summed once.
  // A resumed run with changes goes on from the step it started with (its model has changed).
  rep.stable_time_step = changes && resume                  ? resume->stable_time_step
                         : changes && changes->stable_step ? changes->stable_step()
                                                           : stable_time_step(model);
  double dt = resume ? resume->dt : opt.dt > 0.0 ? opt.dt : opt.safety * rep.stable_time_step;
  // A step of 0 ran every step to t = 0 and ended in success; one not finite ran none.
  if (!(std::isfinite(dt) && dt > 0.0)) {
    char what[400];
    std::snprintf(what, sizeof what,
                  "Verlet: the stable step estimate is %.4g s (2 / omega_max, omega_max^2 the largest stiffness row "
                  "sum over its lumped mass), so the time step safety x estimate is %.4g s: no step to integrate "
                  "with (a mass too small or a stiffness too large for double precision)",
                  rep.stable_time_step, dt);
    throw StableStepError(what);
  }
  rep.changes.final_dt = dt;  // (a run resumed at its last step runs no step: it read 0)
  if (progress && !resume && opt.dt > rep.stable_time_step && rep.stable_time_step > 0.0) {
    char what[400];
    std::snprintf(what, sizeof what,
                  "solver.dt = %.4g s is %.3g times the stable step estimate %.4g s (2 / omega_max by Gershgorin, "
                  "a lower bound of the limit): the run may be stable, and if it is not the energy guard stops it "
                  "(exit 3); dt: 0 takes safety times the estimate",
                  opt.dt, opt.dt / rep.stable_time_step, rep.stable_time_step);
    progress->warn(what);
  }
  // Kept when changes lower the stable step (0: no finite stable step to follow).
  const double dt_per_stable = changes && resume ? resume->dt_per_stable
                               : std::isfinite(rep.stable_time_step) && rep.stable_time_step > 0.0
                                   ? dt / rep.stable_time_step
                                   : 0.0;
  auto inv_mass = model.lumped_mass();
  for (auto& m : inv_mass) m = 1.0 / m;
  const double* fext = loading.force.empty() ? nullptr : loading.force.data();
  // u_old, v_old: the state of the previous step, the last one that passed the guard.
  std::vector<double> a(n), fint(n), u_old(u), v_old(v);
  // With the energy guard: the last state whose balance was checked (a history row's). A run
  // stopped by the guard ends there, not on the step before the failure, whose energy nobody
  // checked (a run stopped at step 20 wrote "the last good state, step 19" with 1e30 m).
  std::vector<double> u_checked, v_checked;
  std::int64_t checked_step = 0;
  double checked_time = 0.0;
  auto checked = [&](std::int64_t step, double t) {
    if (!opt.energy_check) return;
    u_checked = u, v_checked = v, checked_step = step, checked_time = t;
  };
  std::vector<double> fint_fixed(loading.fixed.size());  // f_int at the constrained dofs, before the step
  rep.history.columns = {"step", "time", "kinetic_energy", "strain_energy", "external_work",
                         "total_energy"};
  const int dpp = model.dofs_per_particle();
  const std::size_t supports = loading.support_names.size() * dpp;
  for (const auto& c : loading.reaction_columns(dpp)) rep.history.columns.push_back(c);
  const std::size_t extra = changes ? 2 : 0;  // broken_bonds, released_energy
  if (changes) rep.history.columns.insert(rep.history.columns.end(), {"broken_bonds", "released_energy"});
  std::size_t changed = changes && resume ? std::size_t(resume->changed) : 0;  // changes made so far
  double released = changes && resume ? resume->released : 0.0;                 // the strain energy they released (J)
  if (changes && resume) rep.changes.changing_steps = resume->changing_steps, rep.changes.step_reductions = resume->step_reductions;
  rep.history.reserve(opt.steps / std::max<std::int64_t>(opt.history_every, 1) + 2);
  auto factor = [&](double t) { return opt.ramp_time > 0.0 ? std::min(1.0, t / opt.ramp_time) : 1.0; };
  // Prescribed velocities ramp with the loads: the displacement v tau(t), tau the integral of
  // factor over [0, t] (t itself without a ramp).
  auto tau = [&](double t) {
    const double T = opt.ramp_time;
    return T > 0.0 ? (t < T ? 0.5 * t * t / T : t - 0.5 * T) : t;
  };
  // External work, trapezoidal in time: over this process's dofs (the history row sums it
  // over the ranks).
  double work = 0.0;
  auto diverged = [&](std::int64_t step, const std::string& what) {
    return DivergenceError("Verlet: " + what + " became NaN or Inf at step " + std::to_string(step), step);
  };
  // The guard, part 1: the acceleration (and so the internal force) is finite. The constrained
  // dofs' forces move to the free dofs they couple to (Galerkin supports), then a = f / m.
  // From fint, the internal force at u (accelerate takes it first; a change updates it).
  auto accelerate_from_force = [&](std::int64_t step, double t) {
    const double s = factor(t);
    parallel_for(n, [&](std::size_t k) { a[k] = (fext ? s * fext[k] : 0.0) - fint[k]; });
    loading.reduce(a.data());
    auto sums = parallel_sums<3>(n, [&](std::size_t k, double* acc) {
      a[k] *= inv_mass[k];
      acc[0] += a[k] * a[k], acc[1] += u[k] * u[k], acc[2] += v[k] * v[k];
    });
    // Over the ranks too: every rank stops at the same step.
    model.sum_across_ranks(sums.data(), 3);
    const auto [a2, u2, v2] = sums;
    if (!std::isfinite(a2 + u2 + v2)) throw diverged(step, "the internal force or the state");
  };
  auto accelerate = [&](std::int64_t step, double t) {
    model.internal_force(u.data(), fint.data());
    accelerate_from_force(step, t);
  };
  // Part 2: the history row (energies, then the supports' static reactions), checked before
  // it is kept; and the energy balance E - E0 - W against the largest energy and work so far.
  double e0 = 0.0, e_max = 0.0, w_max = 0.0;
  std::vector<double> row;
  auto energies = [&](std::int64_t step, double t) {
    auto [kin, mu2] = parallel_sums<2>(n, [&](std::size_t k, double* acc) {
      acc[0] += 0.5 * v[k] * v[k] / inv_mass[k], acc[1] += u[k] * u[k] / inv_mass[k];
    });
    double strain = model.energy(u.data());
    row.assign({double(step), t, kin, strain, work, 0.0});
    row.resize(6 + supports + extra);
    // fint is the force at this state (accelerate ran on it): the supports' static reaction.
    if (supports > 0) loading.reactions(fint.data(), factor(t), dpp, row.data() + 6);
    // The energies, the work and the reactions over the ranks: row[5] (the total, set below)
    // is 0 here and rides along, so that one sum reaches the last reaction column.
    model.sum_across_ranks(row.data() + 2, int(4 + supports));
    const double all_work = row[4];
    kin = row[2], strain = row[3];
    row[5] = kin + strain + released - all_work;
    if (changes) row[6 + supports] = double(changed), row[7 + supports] = released;
    for (const double x : row)
      if (!std::isfinite(x)) throw diverged(step, "an energy or a reaction");
    if (step == 0) e0 = kin + strain;
    e_max = std::max(e_max, kin + strain), w_max = std::max(w_max, std::abs(all_work));
    const double defect = std::abs(kin + strain + released - e0 - all_work);
    model.sum_across_ranks(&mu2, 1);
    const double floor = rounding_energy(dt_per_stable > 0.0 ? dt / dt_per_stable : rep.stable_time_step, mu2);
    const double bound = opt.energy_tolerance * std::max(e_max, w_max) + floor;
    if (opt.energy_check && defect > bound) {
      rep.history.values.insert(rep.history.values.end(), row.begin(), row.end());  // the evidence, in history.csv
      char what[640];
      std::snprintf(what, sizeof what,
                    "Verlet: the energy balance failed at step %lld (t = %.4e s): kinetic + strain energy "
                    "%.4e J against %.4e J initial plus %.4e J of external work, off by %.3e J, more than %g times "
                    "the largest energy or work so far plus the rounding floor %.3e J (the discrete problem gains "
                    "energy: an unstable formulation or time step; solver.energy_check: false turns this guard off)",
                    static_cast<long long>(step), t, kin + strain, e0, all_work, defect, opt.energy_tolerance, floor);
      throw SolveErrorOnEveryRank(what);  // (its sums are over the ranks: alike on every rank)
    }
  };
  auto record = [&]() { rep.history.values.insert(rep.history.values.end(), row.begin(), row.end()); };
  double t = 0.0;
  // Galerkin supports whose targets move (a prescribed displacement): their multipliers, on
  // every rank if on one (a distributed loading solves them over the ranks).
  double moving = loading.galerkin() && (loading.has_rates() || std::any_of(loading.value.begin(), loading.value.end(),
                                                                             [](double x) { return x != 0.0; }))
                      ? 1.0
                      : 0.0;
  model.max_across_ranks(&moving, 1);
  const bool moving_galerkin = moving > 0.0;
  std::vector<double> lambda(moving_galerkin ? loading.fixed.size() : 0), lambda_old(lambda.size());
  std::int64_t first_step = 1;
  if (resume) {
    for (const auto* x : {&resume->u, &resume->v, &resume->a, &resume->fint})
      if (x->size() != n) throw std::invalid_argument("solve_verlet: a resumed state vector does not have dofs() values");
    if (resume->multipliers.size() != lambda.size() || resume->history.size() % rep.history.columns.size())
      throw std::invalid_argument("solve_verlet: the resumed state's multipliers or history do not fit the loading");
    u = resume->u, v = resume->v, a = resume->a, fint = resume->fint, lambda_old = resume->multipliers;
    t = resume->time, work = resume->work, e0 = resume->e0, e_max = resume->e_max, w_max = resume->w_max;
    rep.history.values.assign(resume->history.begin(), resume->history.end());
    rep.iterations = resume->step, rep.end_time = t;
    first_step = resume->step + 1;
    checked(resume->step, t);
  } else {
    loading.impose(factor(t), u.data(), tau(t));
    accelerate(0, t);
    if (moving_galerkin) loading.multipliers(fint.data(), factor(t), lambda_old.data());
    energies(0, t);
    record();
    checked(0, t);
  }
  ProgressSample sample;
  sample.limit = opt.steps;
  ThreadGovernor governor;
  const double loop_start = wall_seconds();
  for (std::int64_t step = first_step; step <= opt.steps; ++step) {
    governor.tick();
    parallel_for(n, [&](std::size_t k) {
      v_old[k] = v[k];
      v[k] += 0.5 * dt * a[k];
      u_old[k] = u[k];
      u[k] += dt * v[k];
    });
    const double t_old = t;
    t += dt;
    try {
      loading.impose(factor(t), u.data(), tau(t));
      const double s_mid = 0.5 * (factor(t) + factor(t - dt));
      if (fext)
        work += s_mid * parallel_sums<1>(n, [&](std::size_t k, double* acc) { acc[0] += fext[k] * (u[k] - u_old[k]); })[0];
      for (std::size_t k = 0; k < loading.fixed.size(); ++k) fint_fixed[k] = fint[loading.fixed[k]];
      accelerate(step, t);
      // The constraints' work. Galerkin supports act through their multipliers on E u = t, so
      // they work only as their targets move: lambda . dt (trapezoidal), zero for fixed ones.
      // Otherwise the load on a constrained dof is replaced by its reaction, and the work
      // there is f_int . du (trapezoidal), zero for supports that do not move.
      if (moving_galerkin) {
        const double ds = factor(t) - factor(t - dt);
        loading.multipliers(fint.data(), factor(t), lambda.data());
        for (std::size_t k = 0; k < loading.fixed.size(); ++k) {
          work += 0.5 * (lambda_old[k] + lambda[k]) * ds * loading.value[k];
          if (!loading.rate.empty())  // velocities
            work += 0.5 * (lambda_old[k] + lambda[k]) * loading.rate[k] * (tau(t) - tau(t - dt));
        }
        std::swap(lambda, lambda_old);
      }
      for (std::size_t k = 0; k < loading.fixed.size() && !loading.galerkin(); ++k) {
        const std::int64_t dof = loading.fixed[k];
        const double du = u[dof] - u_old[dof];
        if (du != 0.0) work += (0.5 * (fint_fixed[k] + fint[dof]) - (fext ? s_mid * fext[dof] : 0.0)) * du;
      }
      parallel_for(n, [&](std::size_t k) { v[k] += 0.5 * dt * a[k]; });
      loading.zero_fixed(v.data());
      // Changes after the step, at its end state (u, v): the step itself ran on the model
      // before them (the work above and the kick are its force's), the next one runs on the
      // changed model from the force taken anew. So each step is an exact Verlet step of one
      // model, and the balance loses only the strain energy the changes release.
      if (changes && step % changes->every == 0) {
        const double t0 = wall_seconds();
        const bool due = changes->find(u.data()) > 0;
        const double t1 = wall_seconds();
        rep.changes.find_seconds += t1 - t0;
        if (due) {
          const ChangesMade made = changes->apply(u.data(), fint.data());
          changed += made.count;
          released += made.released;
          if (changes->stable_step && dt_per_stable > 0.0) {
            const double lowered = dt_per_stable * changes->stable_step();
            if (lowered < dt) dt = lowered, ++rep.changes.step_reductions;
          }
          accelerate_from_force(step, t);
          rep.changes.change_seconds += wall_seconds() - t1;
          ++rep.changes.changing_steps;
        }
      }
      // Every history_every steps, and the last: a run of 35 steps at 10 ended its history at
      // step 30, without the final state's energies and reactions.
      const bool keep_row = step % opt.history_every == 0 || step == opt.steps;
      if (keep_row) energies(step, t);
      observe(step, t, u);  // part 3: the snapshot writer refuses a non-finite field
      if (keep_row) record(), checked(step, t);
    } catch (const SolveError& e) {
      const auto* d = dynamic_cast<const DivergenceError*>(&e);
      if (!opt.energy_check) {
        u.swap(u_old), v.swap(v_old);
        rep.end_time = t_old;  // rep.iterations is still step - 1
        throw DivergenceError(std::string(e.what()) + "; the last good state is step " + std::to_string(step - 1),
                              d ? d->step : step);
      }
      u.swap(u_checked), v.swap(v_checked);
      rep.end_time = checked_time, rep.iterations = checked_step;
      throw DivergenceError(std::string(e.what()) + "; the last good state is step " + std::to_string(checked_step) +
                                ", the last whose energy balance was checked (every solver.history_every steps)",
                            d ? d->step : step);
    }
    rep.iterations = step;
    rep.end_time = t;
    rep.changes.loop_seconds = wall_seconds() - loop_start;  // also right when a later step fails
    rep.changes.final_dt = dt;
    if (progress && step % 50 == 0) {
      sample.iteration = step;
      sample.time = t;
      if (changes) sample.broken = static_cast<std::int64_t>(changed);
      sample.history = &rep.history;
      progress->update(sample);
    }
    if (checkpoints.due(step)) {
      VerletState s;
      s.step = step, s.time = t, s.dt = dt, s.work = work, s.e0 = e0, s.e_max = e_max, s.w_max = w_max;
      s.u = u, s.v = v, s.a = a, s.fint = fint, s.multipliers = lambda_old, s.history = rep.history.values;
      if (changes && changes->save) {
        s.stable_time_step = rep.stable_time_step, s.dt_per_stable = dt_per_stable, s.changed = double(changed), s.released = released;
        s.changing_steps = rep.changes.changing_steps, s.step_reductions = rep.changes.step_reductions;
        s.changes = changes->save();
      }
      checkpoints.call(s);
    }
  }
  rep.converged = true;
  if (progress) progress->finish();
}

/// A failure's message, with what a given step has to do with it: a `dt` above the stable
/// step estimate (a lower bound of the true limit) is the first suspect when a run diverges.
std::string with_step_note(const std::string& what, const VerletOptions& opt, const SolveReport& rep) {
  if (!(opt.dt > 0.0) || !(rep.stable_time_step > 0.0) || opt.dt <= rep.stable_time_step) return what;
  char note[320];
  std::snprintf(note, sizeof note,
                "; solver.dt = %.4g s is %.3g times the stable step estimate %.4g s (2 / omega_max by Gershgorin, a "
                "lower bound of the limit): a smaller dt, or dt: 0 for safety times the estimate",
                opt.dt, opt.dt / rep.stable_time_step, rep.stable_time_step);
  return what + note;
}

}  // namespace

SolveReport solve_verlet(Model& model, const Loading& loading, const VerletOptions& opt,
                         std::vector<double>& u, std::vector<double>& v, Progress* progress,
                         const Observer& observe, const Checkpoints<VerletState>& checkpoints,
                         const VerletState* resume, const ModelChanges* changes) {
  check_loading(loading, model.dofs());
  SolveReport rep;
  try {
    integrate(model, loading, opt, u, v, progress, observe, checkpoints, resume, changes, rep);
  } catch (const DivergenceError& e) {
    if (progress) progress->finish();
    rep.converged = false;
    rep.diverged = true;
    rep.diverged_at = e.step;
    rep.failure = with_step_note(e.what(), opt, rep);
  } catch (const SolveError& e) {
    if (progress) progress->finish();
    rep.converged = false;
    rep.failure = with_step_note(e.what(), opt, rep);
  }
  return rep;
}

}  // namespace perinom

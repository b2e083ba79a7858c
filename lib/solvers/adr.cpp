#include "perinom/solvers/adr.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "perinom/core/error.hpp"
#include "perinom/core/parallel.hpp"
#include "perinom/core/thread_governor.hpp"
#include "perinom/solvers/rounding_force.hpp"

namespace perinom {

AdrRelaxation::AdrRelaxation(Model& model, const AdrOptions& opt, Progress* progress)
    : model_(model), opt_(opt), progress_(progress) {
  const std::size_t n = model.dofs();
  // The diagonal mass lambda = 1/4 sum_j |K_ij| (dt = 1), kept as its inverse.
  if (progress) progress->phase("summing the stiffness rows for the ADR mass");
  inv_lambda_ = model.stiffness_row_sums();
  for (auto& l : inv_lambda_) l = 4.0 / l;
  v_.resize(n), f_.resize(n), f_old_.resize(n), fint_.resize(n);
  sample_.limit = opt.max_iterations;
  sample_.load_steps = opt.load_steps;
  sample_.target = opt.tolerance;
}

void AdrRelaxation::raise_density(const std::vector<double>& row_sums) {
  if (row_sums.size() != inv_lambda_.size())
    throw std::invalid_argument("AdrRelaxation::raise_density: " + std::to_string(row_sums.size()) + " row sums for " +
                                std::to_string(inv_lambda_.size()) + " dofs");
  if (first_inv_lambda_.empty()) first_inv_lambda_ = inv_lambda_;
  for (std::size_t k = 0; k < inv_lambda_.size(); ++k)
    inv_lambda_[k] = row_sums[k] > 0.0 ? std::min(first_inv_lambda_[k], 4.0 / row_sums[k]) : first_inv_lambda_[k];
}

void AdrRelaxation::resume(const AdrState& st) {
  const std::size_t n = model_.dofs();
  for (const auto* x : {&st.u, &st.v, &st.f, &st.f_old, &st.inv_lambda})
    if (x->size() != n)
      throw std::invalid_argument("AdrRelaxation::resume: a state vector holds " + std::to_string(x->size()) +
                                  " values for " + std::to_string(n) + " dofs");
  inv_lambda_ = st.inv_lambda, v_ = st.v, f_ = st.f, f_old_ = st.f_old;
  resume_r_ = st.residual, resume_du_ = st.displacement_change, resume_c_ = st.damping;
  resuming_ = true;
}

AdrState AdrRelaxation::state(const std::vector<double>& u, double r, double du, double c, const SolveReport& rep) const {
  return {sample_.load_step, rep.iterations, r, du, c, u, v_, f_, f_old_, inv_lambda_, rep.history.values};
}

void AdrRelaxation::add_reactions(const Loading& loading, double s, History& history) {
  if (!loading.has_supports()) return;
  const int dpp = model_.dofs_per_particle();
  const std::size_t at = history.values.size();
  history.values.resize(at + loading.support_names.size() * dpp);
  loading.reactions(fint_.data(), s, dpp, history.values.data() + at);
  model_.sum_across_ranks(history.values.data() + at, int(history.values.size() - at));
}

bool AdrRelaxation::balance(const Loading& loading, double s, std::vector<double>& u,
                            SolveReport& rep, const Observer& observe,
                            const std::function<void()>& after_iteration) {
  const std::size_t n = model_.dofs();
  u.resize(n, 0.0);
  last_good_ = u;
  rep.at_rounding_floor = false;  // this balance's
  model_.follow_loads(loading, s);
  auto& v = v_;
  auto& f = f_;
  auto& f_old = f_old_;
  const auto& inv_lambda = inv_lambda_;
  // Every sum below is over this process's dofs, then over the ranks (Model::sum_across_ranks).
  double force_norm2 = loading.force_norm(s);
  force_norm2 *= force_norm2;
  model_.sum_across_ranks(&force_norm2, 1);
  const double force_norm = std::sqrt(force_norm2);
  const bool forced = loading.has_force();

  // |F| (N) in `force` and the load it is relative to in `carried`, from f and fint_; returns
  // the relative residual.
  double force = std::numeric_limits<double>::infinity(), carried = 0.0;
  // The stiffest row sum: in equilibrium |u| >= |f_int| / max_k sum_j |K_kj| >= carried / it.
  double stiffest = 0.0;
  for (const double il : inv_lambda) stiffest = std::max(stiffest, 4.0 / il);
  model_.max_across_ranks(&stiffest, 1);
  auto measure = [&]() {
    double reaction2 = 0.0;
    for (const auto dof : loading.fixed) reaction2 += fint_[dof] * fint_[dof];
    const double* fp = f.data();
    double sums[2] = {reaction2, parallel_sums<1>(n, [fp](std::size_t k, double* a) { a[0] += fp[k] * fp[k]; })[0]};
    model_.sum_across_ranks(sums, 2);
    reaction2 = sums[0];
    const double fnorm = std::sqrt(sums[1]);
    if (!std::isfinite(fnorm) || !std::isfinite(reaction2))
      throw DivergenceError("ADR: the internal force became NaN or Inf at iteration " +
                            std::to_string(rep.iterations + 1), rep.iterations + 1);
    const double load = std::max({force_norm, std::sqrt(reaction2), load_floor_});
    force = fnorm, carried = load;
    return load > 0.0 ? fnorm / load : fnorm;
  };
  // Residual force F = f_ext(s) - f_int on the free dofs; returns the relative residual.
  auto residual = [&]() {
    model_.internal_force(u.data(), fint_.data());
    parallel_for(n, [&](std::size_t k) { f[k] = (forced ? loading.force_at(s, k) : 0.0) - fint_[k]; });
    loading.reduce(f.data());
    return measure();
  };
  // The size of the terms the internal force at u sums (N, over the ranks): its rounding is
  // rounding_force of it.
  auto stiffness = [&]() {
    const double* il = inv_lambda.data();
    double fs = stiffness_force(n, u.data(), [il](std::size_t k) { return 4.0 / il[k]; });
    fs *= fs;
    model_.sum_across_ranks(&fs, 1);
    return std::sqrt(fs);
  };

  double r = 0.0, du = 1.0, c = 0.0;
  bool first = true, converged = false;
  if (resuming_) {
    // v, f and f_old are the resumed state's, u is where it stopped: the next iteration is
    // the one the interrupted solve would have made (its damping needs f_old).
    resuming_ = false;
    r = resume_r_, du = resume_du_, c = resume_c_, first = false;
    // The reactions and |F| at u, from the resumed F (not recomputed: F is the interrupted
    // run's, bit for bit): a solve that stops at once writes its last row from them.
    model_.internal_force(u.data(), fint_.data());
    measure();
  } else {
    loading.impose(s, u.data());
    std::fill(v.begin(), v.end(), 0.0);
    try {
      r = residual();
    } catch (const DivergenceError&) {
      throw DivergenceError("ADR: the internal force of the starting state is NaN or Inf", rep.iterations);
    }
  }
  ThreadGovernor governor;
  const std::vector<double> u_start = by_correction_ ? u : std::vector<double>{};
  while (rep.iterations < opt_.max_iterations) {
    governor.tick();
    // The seed's criterion (eq. 33) alone stops a solve that has barely moved; the
    // residual criterion makes sure it is in equilibrium. A residual force at the rounding
    // floor is equilibrium too: where the loads and reactions are themselves rounding (a
    // stress-free rigid motion) the relative residual is rounding over rounding, 0.6 after
    // 200,000 iterations, while |F| sat at a fifth of the floor.
    if (!first && du <= opt_.displacement_tolerance && r > opt_.tolerance && force <= rounding_force(stiffness())) {
      converged = true;
      rep.at_rounding_floor = true;
      break;
    }
    if (!first && r <= opt_.tolerance && du <= opt_.displacement_tolerance) {
      converged = true;
      break;
    }
    if (first) {
      parallel_for(n, [&](std::size_t k) { v[k] = 0.5 * f[k] * inv_lambda[k]; });
    } else {
      // Damping from the local diagonal stiffness (Rayleigh quotient over u; with
      // by_correction_ also over the correction w = u - u_start, the smaller taken).
      auto quotient = parallel_sums<4>(n, [&](std::size_t k, double* acc) {
        const double w = by_correction_ ? u[k] - u_start[k] : 0.0;
        acc[1] += u[k] * u[k], acc[3] += w * w;
        if (v[k] != 0.0) {
          const double stiffness = -(f[k] - f_old[k]) * inv_lambda[k] / v[k];
          acc[0] += u[k] * u[k] * stiffness, acc[2] += w * w * stiffness;
        }
      });
      model_.sum_across_ranks(quotient.data(), 4);
      const double num = quotient[0], den = quotient[1];
      c = (num > 0.0 && den > 0.0) ? 2.0 * std::sqrt(num / den) : 0.0;
      if (quotient[2] > 0.0 && quotient[3] > 0.0) c = std::min(c, 2.0 * std::sqrt(quotient[2] / quotient[3]));
      c = std::min(c, 1.999);
      const double keep = (2.0 - c) / (2.0 + c), push = 2.0 / (2.0 + c);
      parallel_for(n, [&](std::size_t k) { v[k] = keep * v[k] + push * f[k] * inv_lambda[k]; });
    }
    first = false;
    loading.zero_fixed(v.data());
    // last_good_: the state of the previous iteration, the last one that passed the guard.
    double moved[2] = {parallel_sums<1>(n, [&](std::size_t k, double* acc) {
      last_good_[k] = u[k];
      u[k] += v[k];
      acc[0] += v[k] * v[k];
    })[0], 0.0};
    if (loading.coupled_constraints()) loading.impose(s, u.data());
    const double* up = u.data();
    moved[1] = parallel_sums<1>(n, [up](std::size_t k, double* a) { a[0] += up[k] * up[k]; })[0];
    model_.sum_across_ranks(moved, 2);
    const double du2 = moved[0], un = std::sqrt(moved[1]);
    // Relative to |u|, or to the least |u| the load carried implies where |u| is smaller:
    // an answer u = 0 (every load on held dofs) made the change rounding over rounding, 0.04
    // after 200,000 iterations at a residual of 2e-17.
    const double u_scale = std::max(un, carried / stiffest);
    du = u_scale > 0.0 ? std::sqrt(du2) / u_scale : std::sqrt(du2);
    f_old.swap(f);
    try {
      // The guard: the force, the change and the damping (the history row) are finite,
      // and the snapshot writer refuses a non-finite field.
      r = residual();
      if (!std::isfinite(du) || !std::isfinite(c))
        throw DivergenceError("ADR: the displacement became NaN or Inf at iteration " +
                              std::to_string(rep.iterations + 1), rep.iterations + 1);
      observe(rep.iterations + 1, s, u);
    } catch (const SolveError& e) {
      u.swap(last_good_);
      const auto* d = dynamic_cast<const DivergenceError*>(&e);
      throw DivergenceError(std::string(e.what()) + "; the last good state is iteration " +
                                std::to_string(rep.iterations),
                            d ? d->step : rep.iterations + 1);
    }
    if (after_iteration) after_iteration();
    ++rep.iterations;
    if (rep.iterations % opt_.history_every == 0) {
      rep.history.add({double(rep.iterations), s, r, du, c});
      add_reactions(loading, s, rep.history);
    }
    if (progress_ && rep.iterations % 50 == 0) {
      sample_.iteration = rep.iterations;
      sample_.residual = r;
      sample_.history = &rep.history;
      progress_->update(sample_);
    }
    if (checkpoints_.due(rep.iterations)) checkpoints_.call(state(u, r, du, c, rep));
  }
  // The last iteration's row, when history_every skipped it: history.csv ends at the state
  // returned.
  const auto& h = rep.history;
  if (rep.iterations > 0 && (h.rows() == 0 || h.at(h.rows() - 1, 0) != double(rep.iterations))) {
    rep.history.add({double(rep.iterations), s, r, du, c});
    add_reactions(loading, s, rep.history);
  }
  rep.residual = r;
  rep.residual_force = force;
  rep.stiffness_force = stiffness();
  rep.displacement_change = du;
  return converged;
}

SolveReport solve_adr(Model& model, const Loading& loading, const AdrOptions& opt,
                      std::vector<double>& u, Progress* progress, const Observer& observe,
                      const Checkpoints<AdrState>& checkpoints, const AdrState* resume) {
  check_loading(loading, model.dofs());
  if (opt.load_steps < 1)
    throw InputError("AdrOptions::load_steps = " + std::to_string(opt.load_steps) + ": must be at least 1");
  SolveReport rep;
  rep.history.columns = {"iteration", "load_factor", "residual", "displacement_change", "damping"};
  for (const auto& c : loading.reaction_columns(model.dofs_per_particle())) rep.history.columns.push_back(c);
  rep.history.reserve(opt.max_iterations / std::max<std::int64_t>(opt.history_every, 1) + 1);
  try {
    AdrRelaxation adr(model, opt, progress);
    adr.set_checkpoints(checkpoints);
    int first_step = 1;
    if (resume) {
      if (resume->load_step < 1 || resume->load_step > opt.load_steps || resume->history.size() % rep.history.columns.size())
        throw std::invalid_argument("solve_adr: the resumed state's load step or history does not fit the options");
      adr.resume(*resume);
      u = resume->u;
      rep.iterations = resume->iterations;
      rep.history.values.assign(resume->history.begin(), resume->history.end());
      first_step = resume->load_step;
    }
    for (int step = first_step; step <= opt.load_steps; ++step) {
      adr.set_load_step(step, opt.load_steps);
      rep.converged = adr.balance(loading, static_cast<double>(step) / opt.load_steps, u, rep, observe);
      if (!rep.converged) break;
    }
  } catch (const DivergenceError& e) {
    rep.converged = false;
    rep.diverged = true;
    rep.diverged_at = e.step;
    rep.failure = e.what();
  } catch (const SolveError& e) {
    rep.converged = false;
    rep.failure = e.what();
  }
  if (progress) progress->finish();
  return rep;
}

}  // namespace perinom

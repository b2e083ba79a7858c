#include "perinom/solvers/load_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "perinom/core/error.hpp"
#include "perinom/core/timer.hpp"
#include "energy_ledger.hpp"
#include "load_path_state.hpp"
#include "unstable_state.hpp"

namespace perinom {
namespace {

// xi of every particle (empty for an elastic model).
std::vector<double> plastic_strains(const Model& model) {
  const ModelHistory* h = model.history();
  return h ? h->history_variable() : std::vector<double>{};
}

/// Whether any particle (of any rank) has plastic strain.
bool plastically_strained(const Model& model) {
  const auto xi = plastic_strains(model);
  double any = std::any_of(xi.begin(), xi.end(), [](double v) { return v > 0.0; }) ? 1.0 : 0.0;
  model.sum_across_ranks(&any, 1);
  return any > 0.0;
}

void count_plastic(const Model& model, const std::vector<double>& xi_before,
                   LoadStepRecord& r) {
  const auto xi = plastic_strains(model);
  double count[2] = {0.0, 0.0};  // yielding, plastic
  for (std::size_t i = 0; i < xi.size(); ++i) {
    count[0] += xi[i] > xi_before[i] ? 1.0 : 0.0;
    count[1] += xi[i] > 0.0 ? 1.0 : 0.0;
  }
  model.sum_across_ranks(count, 2);  // (over ranks: each counts its own particles)
  r.yielding = std::size_t(count[0]), r.plastic = std::size_t(count[1]);
}

/// How a failed balance's residual (relative, `total`) splits between the particles the
/// changes detached and the rest of the body, at the state the balance stopped in: "; of
/// it, a on the N detached particles and b on the rest" (a^2 + b^2 = total^2), or nothing
/// when none are detached. f is scratch of model.dofs().
std::string residual_split(Model& model, const ModelChanges* changes, const Loading& loading, double s,
                           const std::vector<double>& u, double total, std::vector<double>& f) {
  if (!changes || !changes->detached) return {};
  const std::vector<ParticleId>& loose = changes->detached();
  if (loose.empty()) return {};
  model.follow_loads(loading, s);
  model.internal_force(u.data(), f.data());
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = (loading.has_force() ? loading.force_at(s, k) : 0.0) - f[k];
  loading.reduce(f.data());  // the free dofs' residual, as ADR measures it
  const int d = model.dofs_per_particle();
  double sums[2] = {0.0, 0.0};  // on the detached particles, on the rest
  for (const double r : f) sums[1] += r * r;
  for (const ParticleId i : loose)
    for (int a = 0; a < d; ++a) {
      const double r = f[std::size_t(i) * d + a];
      sums[0] += r * r, sums[1] -= r * r;
    }
  model.sum_across_ranks(sums, 2);
  const double all = sums[0] + std::max(sums[1], 0.0);
  if (!(all > 0.0)) return {};
  char text[160];
  std::snprintf(text, sizeof text, "; of it, %.3e on the %zu detached particles and %.3e on the rest of the body",
                total * std::sqrt(sums[0] / all), loose.size(), total * std::sqrt(std::max(sums[1], 0.0) / all));
  return text;
}

/// Why a step under force control may have no balanced state, for a failed balance's
/// message: a cracking or yielding body carries only so much. `moved`: how far the
/// balance carried the displacement from the step's start over the previous step's increment
/// (0 when unknown); a plastic mechanism shows itself by a displacement that runs away.
std::string past_capacity(bool cracking, bool plastic, double moved) {
  if (cracking)
    return "the stage's forces are more than the cracking body can carry: to follow its path past the peak, "
           "move the loaded region by a displacement";
  if (!plastic) return {};
  char how_far[96] = "";
  if (moved > 0.0)
    std::snprintf(how_far, sizeof how_far, ", and this balance moved the body %.3g times the last step's increment",
                  moved);
  return std::string("the stage's forces are more than the plastic body can carry (past its limit load a "
                     "mechanism flows and no balanced state exists") +
         how_far + "): to reach the limit load, move the loaded region by a displacement and read its reaction";
}

std::string stage_name(const LoadStage& stage, int k) {
  return "stage " + std::to_string(k + 1) + " (" + stage.name + ")";
}

std::string where(const LoadStage& stage, int k, int step) {
  return stage_name(stage, k) + " load step " + std::to_string(step);
}

/// The path's report keeps its last balance's residual force, stiffness force and rounding
/// floor (the final state's, for the closing line and the equilibrium error).
void keep_floor(const SolveReport& step, SolveReport& path) {
  path.residual_force = step.residual_force, path.stiffness_force = step.stiffness_force;
  path.at_rounding_floor = step.at_rounding_floor;
}

}  // namespace

bool parse_load_path_scheme(const std::string& type, LoadPathScheme& s) {
  if (type == "lbc") s = LoadPathScheme::lbc;
  else if (type == "adr") s = LoadPathScheme::every_iteration;
  else if (type == "newton") s = LoadPathScheme::newton;
  else return false;
  return true;
}

SolveReport solve_load_path(Model& model, std::vector<LoadStage>& stages,
                            const LoadPathOptions& opt, std::vector<double>& u, Progress* progress,
                            const std::function<void(const LoadStepRecord&, const std::vector<double>&)>&
                                after_step,
                            const Checkpoints<LoadPathState>& checkpoints, const LoadPathState* resume,
                            const ModelChanges* changes) {
  for (std::size_t k = 0; k < stages.size(); ++k) {
    check_loading(stages[k].loading, model.dofs(), false);  // begin_stage sets each start
    if (stages[k].steps < 1)
      throw InputError("LoadStage::steps of stage " + std::to_string(k) + " = " + std::to_string(stages[k].steps) +
                       ": must be at least 1");
  }
  if (opt.scheme == LoadPathScheme::newton && (checkpoints.every > 0 || resume))
    throw std::invalid_argument("solve_load_path: the Newton scheme is not checkpointed (KINSOL's state is not kept)");
  if (opt.scheme == LoadPathScheme::newton && changes)
    throw std::invalid_argument("solve_load_path: bonds break on the lbc and adr schemes, not Newton's");
  if (changes && (checkpoints.every > 0 || resume) && !(changes->save && changes->restore))
    throw std::invalid_argument("solve_load_path: changes that cannot save and restore themselves are not checkpointed");
  SolveReport rep;
  rep.history.columns = {"stage", "step", "load_factor", "iterations", "rounds", "newly_flagged",
                         "yielding", "plastic", "residual", "seconds"};
  u.resize(model.dofs(), 0.0);
  // Reactions: one column per support of any stage (the scene's items are in every stage);
  // a support absent from a stage reacts with 0 there.
  const int d = model.dofs_per_particle();
  Loading supports;
  for (const auto& st : stages)
    for (const auto& name : st.loading.support_names) supports.add_support(name);
  for (const auto& c : supports.reaction_columns(d)) rep.history.columns.push_back(c);
  if (changes) rep.history.columns.push_back("broken_bonds");
  std::vector<double> fint(supports.has_supports() || changes ? model.dofs() : 0), stage_reactions;
  ModelHistory* plastic = model.history();
  // Why a step failed, when `state` (stage's loading at factor s: the state left by ADR, the
  // last converged one by Newton) is unstable.
  const auto unstable = [&](const LoadStage& stage, double s, const std::vector<double>& state,
                            const char* which = "the state left") {
    const std::string why = opt.diagnose_unstable_state ? detail::unstable_state(model, stage.loading, s, state) : "";
    return why.empty() ? why : "; " + std::string(which) + " is " + why;
  };
  // An elastic body that breaks: the work done on it and the energy its breaks dissipated
  // (external work less the strain energy now; energy_ledger.hpp).
  std::optional<EnergyLedger> ledger;
  if (changes && !plastic) {
    rep.history.columns.push_back("external_work");
    rep.history.columns.push_back("dissipated_energy");
  }
  if (plastic)
    plastic->set_history_mode(opt.scheme == LoadPathScheme::lbc ? HistoryMode::flagged : HistoryMode::return_map);
  AdrOptions balance_opt = opt.adr;
  balance_opt.history_every = balance_opt.max_iterations + 1;  // no per-iteration rows
  std::optional<AdrRelaxation> adr;
  if (opt.scheme != LoadPathScheme::newton) adr.emplace(model, balance_opt, progress);
  int total_steps = 0, done = 0;
  for (const auto& s : stages) total_steps += s.steps;
  // Where to start: the first step of the first stage, or the step after the resumed one
  // (the next stage's first when the resumed step ended its stage).
  std::size_t first_stage = 0;
  int first_step = 1;
  bool continuing = false;  // the resumed stage has steps left
  if (resume) {
    done = detail::restore(model, stages, *resume, u, rep);
    if (changes) {
      if (resume->changes.empty()) throw std::invalid_argument("solve_load_path: the resumed state holds no record of the changes");
      changes->restore(resume->changes);
      // The steps that broke bonds, from the rows so far.
      const std::size_t width = rep.history.columns.size();
      const std::size_t column = rep.history.column("broken_bonds");
      for (std::size_t at = column; at < rep.history.values.size(); at += width)
        if (rep.history.values[at] > 0.0) ++rep.changes.changing_steps;
    }
    rep.residual_force = resume->residual_force, rep.stiffness_force = resume->stiffness_force;
    rep.at_rounding_floor = resume->at_rounding_floor;
    first_stage = std::size_t(resume->stage), first_step = resume->step + 1;
    continuing = first_step <= stages[first_stage].steps;
    if (!continuing) ++first_stage, first_step = 1;
  }
  // A refreshed row can be stiffer than it was: ADR's density follows the row sums the
  // changes keep (summed once here, then on the rows each change touches).
  const bool follow_density = changes && changes->stable_step && changes->row_sums && adr;
  double carried = resume ? resume->carried : 0.0;  // the largest reaction norm so far
  double path_load = carried;  // the largest load or reaction norm of the steps so far (Newton's load_floor)
  if (changes && adr) adr->set_load_floor(carried);
  if (changes && adr && changes->dissipates) adr->damp_by_correction(true);
  if (follow_density) {
    changes->stable_step();
    adr->raise_density(changes->row_sums());
  }
  if (changes && !plastic) {
    // Where the path stands: at rest, or the resumed step's balanced state and its row.
    const std::size_t rows = rep.history.rows();
    ledger.emplace(model, u, rows ? rep.history.at(rows - 1, rep.history.column("external_work")) : 0.0,
                   rows ? rep.history.at(rows - 1, rep.history.column("dissipated_energy")) : 0.0);
  }

  auto record = [&](LoadStepRecord& r, const std::vector<double>& xi0, double t0) {
    count_plastic(model, xi0, r);
    r.seconds = wall_seconds() - t0;
    rep.history.add({double(r.stage), double(r.step), r.load_factor, double(r.iterations), double(r.rounds),
                     double(r.newly_flagged), double(r.yielding), double(r.plastic), r.residual, r.seconds});
    if (supports.has_supports()) {
      const Loading& loading = stages[r.stage - 1].loading;
      model.follow_loads(loading, r.load_factor);
      model.internal_force(u.data(), fint.data());
      stage_reactions.resize(loading.support_names.size() * d);
      loading.reactions(fint.data(), r.load_factor, d, stage_reactions.data());
      model.sum_across_ranks(stage_reactions.data(), int(stage_reactions.size()));  // (over ranks: each its own supports' share)
      double reaction2 = 0.0;
      for (const double c : stage_reactions) reaction2 += c * c;
      path_load = std::max(path_load, std::sqrt(reaction2));
      const std::size_t at = rep.history.values.size();
      rep.history.values.resize(at + supports.support_names.size() * d, 0.0);
      for (std::size_t g = 0; g < loading.support_names.size(); ++g)
        for (int a = 0; a < d; ++a)
          rep.history.values[at + supports.add_support(loading.support_names[g]) * d + a] = stage_reactions[g * d + a];
    }
    if (opt.scheme == LoadPathScheme::newton) {
      double applied = stages[r.stage - 1].loading.force_norm(r.load_factor);
      applied *= applied;
      model.sum_across_ranks(&applied, 1);
      path_load = std::max(path_load, std::sqrt(applied));
    }
    if (changes) rep.history.values.push_back(double(r.broken));
    if (ledger) rep.history.add({ledger->work(), ledger->dissipated()});
    rep.residual = r.residual;
    r.rows = &rep.history;
    if (after_step) after_step(r, u);
  };

  try {
    for (std::size_t k = first_stage; k < stages.size(); ++k) {
      LoadStage& stage = stages[k];
      const bool resumed_stage = continuing && k == first_stage;
      if (!resumed_stage) stage.loading.begin_stage(k > 0 ? &stages[k - 1].loading : nullptr, u.data());
      if (opt.scheme == LoadPathScheme::newton) {
        NewtonOptions nopt = opt.newton;
        nopt.load_steps = stage.steps;
        nopt.load_floor = path_load;
        std::vector<double> xi0 = plastic_strains(model);
        double t0 = wall_seconds();
        nopt.before_step = [&](int) {
          if (plastic) plastic->begin_step();
        };
        nopt.after_step = [&](int step, const std::vector<double>& un, long iterations, double residual) {
          if (plastic) plastic->commit(un.data());
          LoadStepRecord r;
          r.stage = static_cast<int>(k) + 1, r.step = step;
          r.load_factor = double(step) / stage.steps;
          r.rounds = 1;
          r.iterations = iterations;
          r.residual = residual;
          record(r, xi0, t0);
          xi0 = plastic_strains(model);
          t0 = wall_seconds();
        };
        // The stage's last converged step and its state: a failed step leaves u at the last
        // good state when the stiffness is singular or the residual not finite, but at KINSOL's
        // last iterate when KINSOL stops otherwise, which is no equilibrium to examine.
        int good = 0;
        std::vector<double> good_u = u;
        const auto commit_step = nopt.after_step;
        nopt.after_step = [&](int step, const std::vector<double>& un, long iterations, double residual) {
          commit_step(step, un, iterations, residual);
          good = step, good_u = un;
        };
        auto* tangent = dynamic_cast<TangentModel*>(&model);
        if (!tangent) throw std::invalid_argument("solve_load_path: the Newton scheme needs a model with a tangent");
        const SolveReport nr = solve_newton(*tangent, stage.loading, nopt, u, progress);
        rep.iterations += nr.iterations;
        keep_floor(nr, rep);
        // (Newton's failures name their load step.)
        const std::string in_stage = stage_name(stage, int(k)) + ": ";
        if (nr.diverged)
          throw DivergenceError(in_stage + nr.failure + unstable(stage, double(good) / stage.steps, good_u, "the last converged state"),
                                done + nr.diverged_at);
        if (!nr.failure.empty()) {
          // A body turning with its loads that has not yielded is not past its limit load (a block
          // turned elastically was told so); a small-strain one's stiffness changes only as it yields.
          const bool yielded = plastic != nullptr && (!model.turns_with_body() || plastically_strained(model));
          throw SolveError(in_stage + nr.failure +
                           (stage.loading.has_force() && yielded ? "; perhaps " + past_capacity(false, true, 0.0) : "") +
                           unstable(stage, double(good) / stage.steps, good_u, "the last converged state"));
        }
        done += stage.steps;
        continue;
      }
      // The predictor: each step starts from the last step's increment extrapolated (zero in
      // a stage's first step). Starting from the previous state with only the boundary moved
      // puts a strain jump under the loaded face, and with non-associated flow (d0 < 1) the
      // balance can then settle in a second, non-uniform equilibrium: the biaxial test did
      // (uniform to 1e-9 with the predictor, 9% lower plastic strain without it).
      std::vector<double> u_prev = resumed_stage ? resume->u_prev : u;
      for (int step = resumed_stage ? first_step : 1; step <= stage.steps; ++step) {
        const double t0 = wall_seconds();
        if (plastic) plastic->begin_step();
        double last_increment = 0.0;  // its norm, for a failed balance's message
        if (step > 1) {
          for (std::size_t k = 0; k < u.size(); ++k) {
            const double increment = u[k] - u_prev[k];
            u_prev[k] = u[k];
            u[k] += increment;
            last_increment += increment * increment;
          }
          model.sum_across_ranks(&last_increment, 1);
        }
        const auto xi0 = plastic_strains(model);
        LoadStepRecord r;
        r.stage = static_cast<int>(k) + 1, r.step = step;
        r.load_factor = static_cast<double>(step) / stage.steps;
        adr->set_load_step(++done, total_steps);
        SolveReport balance;
        std::vector<double> balanced;  // u after this step's last balance that converged
        const std::function<void()> commit_each = [plastic] { plastic->commit_trial(); };
        for (;;) {
          bool ok = false;
          try {
            ok = adr->balance(stage.loading, r.load_factor, u, balance, {},
                              opt.scheme == LoadPathScheme::every_iteration && plastic ? commit_each
                                                                                       : std::function<void()>{});
          } catch (const DivergenceError& e) {
            u = u_prev;  // the last good state: the previous load step's
            throw DivergenceError(where(stage, int(k), step) + ": " + e.what() + " (the last good state is load step " +
                                      std::to_string(done - 1) + ")" + unstable(stage, double(step - 1) / stage.steps, u),
                                  done);
          }
          ++r.rounds;
          r.iterations = balance.iterations;
          r.residual = balance.residual;
          if (!ok) {
            char residual[200];  // (std::to_string's fixed six decimals printed 1.8e-8 as 0.000000)
            std::snprintf(residual, sizeof residual, "%.3e, target %.1e", balance.residual, opt.adr.tolerance);
            if (balance.residual <= opt.adr.tolerance)  // (the message showed a residual below its target alone)
              std::snprintf(residual + std::strlen(residual), sizeof residual - std::strlen(residual),
                            ", met; the displacement change %.3e did not meet solver.displacement_tolerance %.1e",
                            balance.displacement_change, opt.adr.displacement_tolerance);
            const std::string split = residual_split(model, changes, stage.loading, r.load_factor, u, balance.residual, fint);
            double moved = 0.0;
            for (std::size_t k = 0; k < u.size(); ++k) moved += (u[k] - u_prev[k]) * (u[k] - u_prev[k]);
            model.sum_across_ranks(&moved, 1);
            // The state left is the last balanced one: this step's previous round, or the last step.
            u = r.rounds > 1 ? balanced : u_prev;
            const bool forced = stage.loading.has_force() && stage.loading.force_norm(r.load_factor) > 0.0;
            // A body with no plastic strain and no particle flagged in this step is not past its
            // limit load (a block turned elastically was told so).
            const bool yielded = plastic != nullptr && (r.newly_flagged > 0 || plastically_strained(model));
            const std::string capacity =
                forced ? past_capacity(changes != nullptr, yielded,
                                       last_increment > 0.0 ? std::sqrt(moved / last_increment) : 0.0)
                       : "";
            throw SolveError(where(stage, int(k), step) + ": the balance did not converge in " +
                             std::to_string(balance.iterations) + " ADR iterations (residual " + residual + split +
                             "); raise solver.max_iterations or loosen the tolerance" +
                             (capacity.empty() ? "" : "; or " + capacity) +
                             unstable(stage, r.rounds > 1 ? r.load_factor : double(step - 1) / stage.steps, u));
          }
          if (changes || plastic) balanced = u;
          if (opt.scheme == LoadPathScheme::lbc && plastic) {
            const std::size_t flagged = plastic->flag_violations(opt.yield_tolerance);
            r.newly_flagged += flagged;
            if (flagged > 0) {
              if (r.rounds >= opt.max_rounds)
                throw SolveError(where(stage, int(k), step) + ": particles still yielding after " +
                                 std::to_string(r.rounds) + " correction rounds (solver.max_rounds)");
              continue;
            }
          }
          if (!changes) break;
          // The balanced state with the changes due there made; a fixed point when none are.
          model.follow_loads(stage.loading, r.load_factor);
          model.internal_force(u.data(), fint.data());
          if (ledger) ledger->balanced(u, fint, r.rounds == 1);
          double reaction2 = 0.0;
          for (const auto dof : stage.loading.fixed) reaction2 += fint[dof] * fint[dof];
          if (std::sqrt(reaction2) > carried) carried = std::sqrt(reaction2), adr->set_load_floor(carried);
          const std::size_t due = changes->find(u.data());
          if (due == 0) {
            if (ledger) ledger->commit(model, u, fint, r.broken > 0 || changes->dissipates);
            break;
          }
          // The cap: the state left is the last balance, its breaks made, the due ones not.
          if (r.rounds >= opt.max_rounds)
            throw SolveError(where(stage, int(k), step) + ": bonds still breaking after " + std::to_string(r.rounds) +
                             " balances (solver.max_rounds): " + std::to_string(r.broken) + " broke in this step, " +
                             std::to_string(due) +
                             " more were due (counted from each particle: a bond due at both counts twice here, "
                             "once in broken_bonds)");
          r.broken += changes->apply(u.data(), fint.data()).count;
          if (follow_density) changes->stable_step(), adr->raise_density(changes->row_sums());
        }
        rep.iterations += r.iterations;
        keep_floor(balance, rep);
        if (r.broken > 0) ++rep.changes.changing_steps;
        if (plastic) plastic->commit(u.data());
        record(r, xi0, t0);
        if (checkpoints.due(done)) {
          LoadPathState st = detail::state_after(model, stages, int(k), step, u, u_prev, rep);
          if (changes) st.changes = changes->save(), st.carried = carried;
          checkpoints.call(st);
        }
      }
    }
    rep.converged = true;
    // A body turning with its loads can balance on an unstable state that nothing in the path
    // disturbs (a pressed block under dead pressures converged, symmetric, then failed the
    // turn); a small-strain body's stiffness changes only by yielding, which LBC tracks.
    if (opt.diagnose_unstable_state && model.turns_with_body() && !stages.empty())
      rep.unstable_end = detail::unstable_state(model, stages.back().loading, 1.0, u);
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

#include "perinom/models/loading.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

#include "perinom/core/error.hpp"

namespace perinom {

void check_loading(const Loading& l, std::size_t dofs, bool with_start) {
  const auto text = [](auto v) { return std::to_string(v); };
  const std::size_t m = l.fixed.size();
  for (std::size_t k = 0; k < m; ++k)
    if (l.fixed[k] < 0 || static_cast<std::size_t>(l.fixed[k]) >= dofs)
      throw InputError("Loading::fixed[" + text(k) + "] = " + text(l.fixed[k]) + ": not a dof of the model's " +
                       text(dofs));
  auto per_constraint = [&](const auto& v, const char* name, bool optional) {
    if (v.size() != m && !(optional && v.empty()))
      throw InputError(std::string("Loading::") + name + " holds " + text(v.size()) + " entries for the " + text(m) +
                       " fixed dofs (Loading::fixed)");
  };
  per_constraint(l.value, "value", false);
  per_constraint(l.rate, "rate", true);
  if (with_start) per_constraint(l.value0, "value0", true);
  per_constraint(l.support, "support", true);
  auto per_dof = [&](const std::vector<double>& v, const char* name) {
    if (!v.empty() && v.size() != dofs)
      throw InputError(std::string("Loading::") + name + " holds " + text(v.size()) + " entries for the model's " +
                       text(dofs) + " dofs");
  };
  per_dof(l.force, "force");
  per_dof(l.pressure_force, "pressure_force");
  if (with_start) per_dof(l.force0, "force0"), per_dof(l.pressure_force0, "pressure_force0");
  if (l.couplings.empty()) return;
  if (l.couplings.size() != m + 1 || l.couplings.front() != 0 ||
      l.couplings.back() != static_cast<Offset>(l.coupled.size()) || l.coef.size() != l.coupled.size())
    throw InputError("Loading::couplings: not a CSR of the " + text(m) + " constraints over Loading::coupled (" +
                     text(l.coupled.size()) + " entries) and Loading::coef (" + text(l.coef.size()) + ")");
  for (std::size_t k = 0; k < m; ++k)
    if (l.couplings[k + 1] < l.couplings[k])
      throw InputError("Loading::couplings: constraint " + text(k) + "'s couplings end before they begin");
  per_constraint(l.scale, "scale", false);
  if (l.ranks) return;  // a rank's couplings read its ghost dofs too, numbered from dofs on
  for (std::size_t c = 0; c < l.coupled.size(); ++c)
    if (l.coupled[c] < 0 || static_cast<std::size_t>(l.coupled[c]) >= dofs)
      throw InputError("Loading::coupled[" + text(c) + "] = " + text(l.coupled[c]) + ": not a dof of the model's " +
                       text(dofs));
}

void Loading::not_converged(const char* what, std::size_t k) const {
  std::string where = "the face-located constraint on dof " + std::to_string(fixed[k]);
  if (!support.empty() && support[k] >= 0) where += " (support '" + support_names[support[k]] + "')";
  throw SolveError(std::string(what) + " did not converge in 200 sweeps: " + where +
                   " changed most in the last one. The constraints of a face read each other "
                   "too strongly for the sweeps (a face point far from its particles on a coarse "
                   "cloud?); hold the support on its particles (at: layer) or refine");
}

void Loading::fix(std::int64_t dof, double v, int support_index, double v_rate) {
  const bool tracked = support_index >= 0 || !support.empty();
  if (tracked) support.resize(fixed.size(), -1);
  const bool rated = v_rate != 0.0 || !rate.empty();  // (rate is still empty before the first dof)
  if (rated) rate.resize(fixed.size(), 0.0);
  for (std::size_t k = 0; k < fixed.size(); ++k)
    if (fixed[k] == dof) {
      value[k] = v;
      if (tracked) support[k] = support_index;
      if (rated) rate[k] = v_rate;
      return;
    }
  fixed.push_back(dof);
  value.push_back(v);
  if (tracked) support.push_back(support_index);
  if (rated) rate.push_back(v_rate);
}

int Loading::add_support(const std::string& name) {
  for (std::size_t g = 0; g < support_names.size(); ++g)
    if (support_names[g] == name) return static_cast<int>(g);
  support_names.push_back(name);
  return static_cast<int>(support_names.size()) - 1;
}

std::vector<std::string> Loading::reaction_columns(int dpp) const {
  std::vector<std::string> out;
  for (const auto& name : support_names)
    for (int a = 0; a < dpp; ++a) out.push_back(name + ".R" + (dpp == 1 ? "" : std::string(1, "xyz"[a])));
  return out;
}

void Loading::impose(double s, double* u, double t) const {
  if (couplings.empty()) {
    for (std::size_t k = 0; k < fixed.size(); ++k) u[fixed[k]] = target(s, k, t);
    return;
  }
  // Gauss-Seidel sweeps until the constrained values stop changing: a face constraint reads
  // the other constrained dofs of its face, and a dynamic run needs E u = t exactly at every
  // step (one sweep a step let them lag behind the free dofs, a delay that pumped energy into
  // the vibrating bar held at its face). Distributed, a round reads the ghost dofs from their
  // owners once and sweeps the owned constraints to convergence with them; the rounds end
  // when a round's first sweep changes nothing on any rank (about 10 sweeps a call, but only
  // the rounds exchange).
  const std::size_t own = ranks ? ranks->owned_dofs() : SIZE_MAX;
  std::size_t worst = 0;
  for (int round = 0; round < 200; ++round) {
    const double* all = ranks ? ranks->with_ghosts(u) : u;
    double first = 0.0, size = 0.0;
    for (int sweep = 0; sweep < 200; ++sweep) {
      double change = 0.0;
      size = 0.0;
      for (std::size_t k = 0; k < fixed.size(); ++k) {
        double sum = 0.0;
        for (Offset c = couplings[k]; c < couplings[k + 1]; ++c) {
          const auto j = static_cast<std::size_t>(coupled[c]);
          sum += coef[c] * (j < own ? u[j] : all[j]);
        }
        const double next = scale[k] * (target(s, k, t) - sum);
        const double d = std::abs(next - u[fixed[k]]);
        if (d > change || d != d) change = d, worst = k;  // (a NaN, once in, stays)
        size = std::max(size, std::abs(next));
        u[fixed[k]] = next;
      }
      if (!std::isfinite(change)) {  // a NaN or Inf state: the solver's guard names it
        if (!ranks) return;
        first = 0.0;  // (over ranks: end the rounds together)
        break;
      }
      if (sweep == 0) first = change;
      if (change <= 1e-15 * size) break;
      if (sweep == 199 && !ranks) not_converged("Loading::impose", worst);
    }
    if (!ranks) return;
    if (ranks->max(first) <= 1e-15 * ranks->max(size)) return;
  }
  not_converged("Loading::impose (over ranks)", worst);
}

double Loading::force_norm(double s) const {
  if (!has_force()) return 0.0;
  const std::size_t n = std::max(force.size(), force0.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) sum += force_at(s, k) * force_at(s, k);
  return std::sqrt(sum);
}

void Loading::begin_stage(const Loading* previous, const double* u) {
  // Distributed, a face constraint reads ghost dofs (every rank exchanges: couplings are
  // sized on every rank of a loading with face constraints).
  const double* x = ranks && coupled_constraints() ? ranks->with_ghosts(u) : u;
  value0.assign(fixed.size(), 0.0);
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    double v = x[fixed[k]];
    if (coupled_constraints()) {
      v /= scale[k];
      for (Offset c = couplings[k]; c < couplings[k + 1]; ++c) v += coef[c] * x[coupled[c]];
    }
    value0[k] = v;
  }
  force0.clear();
  if (previous && previous->has_force()) {
    const std::size_t n = std::max(previous->force.size(), previous->force0.size());
    force0.resize(n);
    for (std::size_t k = 0; k < n; ++k) force0[k] = previous->force_at(1.0, k);
  }
  pressure_force0.clear();
  if (previous && previous->has_pressure()) {
    const std::size_t n = std::max(previous->pressure_force.size(), previous->pressure_force0.size());
    pressure_force0.resize(n);
    for (std::size_t k = 0; k < n; ++k) pressure_force0[k] = previous->pressure_force_at(1.0, k);
  }
}

void Loading::zero_fixed(double* r) const {
  for (const auto dof : fixed) r[dof] = 0.0;
}

void Loading::index_couplings() {
  std::unordered_map<std::int64_t, std::int64_t> constraint_of;
  for (std::size_t k = 0; k < fixed.size(); ++k) constraint_of[fixed[k]] = static_cast<std::int64_t>(k);
  coupled_constraint.assign(coupled.size(), -1);
  for (std::size_t c = 0; c < coupled.size(); ++c) {
    const auto it = constraint_of.find(coupled[c]);
    if (it != constraint_of.end()) coupled_constraint[c] = it->second;
  }
  lambda_.assign(fixed.size(), 0.0);
  sum_.assign(fixed.size(), 0.0);
  remote_.assign(fixed.size(), 0.0);
}

template <class RAt>
void Loading::solve_multipliers(const RAt& r_at) const {
  const std::size_t m = fixed.size();
  if (coupled_constraint.size() != coupled.size() || lambda_.size() != m)
    throw std::logic_error("Loading: index_couplings() was not called after the couplings changed");
  // (E_FF)^T lambda = -r_F by Jacobi sweeps: E_FF is its diagonal 1/scale plus the small
  // couplings among constrained dofs of one face (a reconstruction reads its neighbours on the
  // face), so the sweeps contract quickly; they stop at rounding. Distributed, couplings also
  // reach constrained dofs of other ranks: a round adds each rank's sums on its ghosts to their
  // owners once (remote_, fixed for the round) and sweeps the owned constraints to convergence;
  // the rounds end when a round's first sweep changes nothing on any rank.
  double size = 0.0;
  for (std::size_t k = 0; k < m; ++k) lambda_[k] = -scale[k] * r_at(fixed[k]), size = std::max(size, std::abs(lambda_[k]));
  if (ranks) size = ranks->max(size);
  if (!(size > 0.0)) return;
  // sum_: the owned constraints' terms on the owned constrained dofs.
  auto local_sums = [&] {
    std::fill(sum_.begin(), sum_.end(), 0.0);
    for (std::size_t k = 0; k < m; ++k)
      for (Offset c = couplings[k]; c < couplings[k + 1]; ++c)
        if (coupled_constraint[c] >= 0) sum_[coupled_constraint[c]] += coef[c] * lambda_[k];
  };
  std::size_t worst = 0;
  for (int round = 0; round < 200; ++round) {
    if (ranks) {
      double* sum = ranks->zeroed_scratch();
      for (std::size_t k = 0; k < m; ++k)
        for (Offset c = couplings[k]; c < couplings[k + 1]; ++c) sum[coupled[c]] += coef[c] * lambda_[k];
      ranks->add_ghosts_to_owners();
      local_sums();
      for (std::size_t l = 0; l < m; ++l) remote_[l] = sum[fixed[l]] - sum_[l];
    }
    double first = 0.0;
    for (int sweep = 0; sweep < 200; ++sweep) {
      local_sums();
      double change = 0.0;
      for (std::size_t l = 0; l < m; ++l) {
        const double next = -scale[l] * (r_at(fixed[l]) + sum_[l] + (ranks ? remote_[l] : 0.0));
        const double d = std::abs(next - lambda_[l]);
        if (d > change || d != d) change = d, worst = l;  // (a NaN, once in, stays)
        lambda_[l] = next;
      }
      if (!std::isfinite(change)) {  // a NaN or Inf force: the solver's guard names it
        if (!ranks) return;
        first = 0.0;  // (over ranks: end the rounds together)
        break;
      }
      if (sweep == 0) first = change;
      if (change <= 1e-15 * size) break;
      if (sweep == 199 && !ranks) not_converged("the face supports' multipliers", worst);
    }
    if (!ranks || ranks->max(first) <= 1e-15 * size) return;
  }
  not_converged("the face supports' multipliers (over ranks)", worst);
}

void Loading::reactions(const double* fint, double s, int dpp, double* R) const {
  std::fill(R, R + support_names.size() * dpp, 0.0);
  const auto residual = [&](std::int64_t dof) { return (has_force() ? force_at(s, dof) : 0.0) - fint[dof]; };
  // Galerkin supports react through their multipliers, spread over the dofs a constraint
  // reads; each row of E sums to one, so a constraint's total is its multiplier.
  if (galerkin()) solve_multipliers(residual);
  for (std::size_t k = 0; k < support.size(); ++k) {
    if (support[k] < 0) continue;
    const std::int64_t dof = fixed[k];
    R[support[k] * dpp + dof % dpp] += galerkin() ? lambda_[k] : -residual(dof);
  }
}

void Loading::multipliers(const double* fint, double s, double* out) const {
  solve_multipliers([&](std::int64_t dof) { return (has_force() ? force_at(s, dof) : 0.0) - fint[dof]; });
  std::copy(lambda_.begin(), lambda_.end(), out);
}

void Loading::reduce(double* r) const {
  if (!galerkin()) return zero_fixed(r);
  solve_multipliers([r](std::int64_t dof) { return r[dof]; });
  if (ranks) {
    // The couplings' shares over the local part, the ghosts' added to their owners (the
    // constrained dofs' shares are zeroed below).
    double* add = ranks->zeroed_scratch();
    for (std::size_t k = 0; k < fixed.size(); ++k)
      for (Offset c = couplings[k]; c < couplings[k + 1]; ++c) add[coupled[c]] += coef[c] * lambda_[k];
    ranks->add_ghosts_to_owners();
    for (std::size_t dof = 0; dof < ranks->owned_dofs(); ++dof) r[dof] += add[dof];
  } else {
    for (std::size_t k = 0; k < fixed.size(); ++k)
      for (Offset c = couplings[k]; c < couplings[k + 1]; ++c)
        if (coupled_constraint[c] < 0) r[coupled[c]] += coef[c] * lambda_[k];
  }
  zero_fixed(r);
}

}  // namespace perinom

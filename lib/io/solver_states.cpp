#include "perinom/io/solver_states.hpp"

#include <string>

#include "perinom/core/error.hpp"

namespace perinom::io {
namespace {

/// A record of whole numbers as int (a stage, a step), refusing values an int does not hold.
int small(const Checkpoint& c, const std::string& name) {
  const std::int64_t v = c.integer(name);
  if (v < 0 || v > 1000000000) throw InputError(c.source + ": the checkpoint's " + name + " is out of range");
  return static_cast<int>(v);
}

}  // namespace

void put_state(Checkpoint& c, const AdrState& s) {
  c.put_integer("adr.load_step", s.load_step);
  c.put_integer("adr.iterations", s.iterations);
  c.put_real("adr.residual", s.residual);
  c.put_real("adr.displacement_change", s.displacement_change);
  c.put_real("adr.damping", s.damping);
  c.put("adr.u", s.u), c.put("adr.v", s.v), c.put("adr.f", s.f), c.put("adr.f_old", s.f_old);
  c.put("adr.inv_lambda", s.inv_lambda), c.put("adr.history", s.history);
}

void put_state(Checkpoint& c, const VerletState& s) {
  c.put_integer("verlet.step", s.step);
  c.put_real("verlet.time", s.time), c.put_real("verlet.dt", s.dt), c.put_real("verlet.work", s.work);
  c.put_real("verlet.e0", s.e0), c.put_real("verlet.e_max", s.e_max), c.put_real("verlet.w_max", s.w_max);
  c.put("verlet.u", s.u), c.put("verlet.v", s.v), c.put("verlet.a", s.a), c.put("verlet.fint", s.fint);
  c.put("verlet.multipliers", s.multipliers), c.put("verlet.history", s.history);
  if (s.changes.empty()) return;  // a model that does not change
  c.put_real("verlet.stable_time_step", s.stable_time_step), c.put_real("verlet.dt_per_stable", s.dt_per_stable);
  c.put_real("verlet.changed", s.changed), c.put_real("verlet.released", s.released);
  c.put_integer("verlet.changing_steps", s.changing_steps), c.put_integer("verlet.step_reductions", s.step_reductions);
  c.put("verlet.changes", s.changes);
}

void put_state(Checkpoint& c, const LoadPathState& s) {
  c.put_integer("load_path.stage", s.stage);
  c.put_integer("load_path.step", s.step);
  c.put_integer("load_path.iterations", s.iterations);
  c.put_real("load_path.residual", s.residual);
  c.put_real("load_path.residual_force", s.residual_force), c.put_real("load_path.stiffness_force", s.stiffness_force);
  c.put_integer("load_path.at_rounding_floor", s.at_rounding_floor ? 1 : 0);
  c.put("load_path.u", s.u), c.put("load_path.u_prev", s.u_prev);
  std::vector<double> value0;
  std::vector<std::int64_t> sizes;
  for (const auto& v : s.stage_value0) value0.insert(value0.end(), v.begin(), v.end()), sizes.push_back(std::int64_t(v.size()));
  c.put("load_path.stage_value0", std::move(value0)), c.put("load_path.stage_value0_sizes", std::move(sizes));
  c.put("load_path.plastic", s.plastic);
  c.put("load_path.flags", std::vector<std::int64_t>(s.flags.begin(), s.flags.end()));
  c.put("load_path.history", s.history);
  if (!s.changes.empty()) c.put("load_path.changes", s.changes), c.put_real("load_path.carried", s.carried);  // bonds that broke
}

AdrState adr_state(const Checkpoint& c, std::size_t n) {
  AdrState s;
  s.load_step = small(c, "adr.load_step");
  s.iterations = c.integer("adr.iterations");
  s.residual = c.real("adr.residual");
  s.displacement_change = c.real("adr.displacement_change");
  if (c.has("adr.damping")) s.damping = c.real("adr.damping");  // (checkpoints before 2026-12-07 lack it: 0)
  s.u = c.reals("adr.u", n), s.v = c.reals("adr.v", n), s.f = c.reals("adr.f", n), s.f_old = c.reals("adr.f_old", n);
  s.inv_lambda = c.reals("adr.inv_lambda", n), s.history = c.reals("adr.history");
  return s;
}

VerletState verlet_state(const Checkpoint& c, std::size_t n) {
  VerletState s;
  s.step = c.integer("verlet.step");
  s.time = c.real("verlet.time"), s.dt = c.real("verlet.dt"), s.work = c.real("verlet.work");
  s.e0 = c.real("verlet.e0"), s.e_max = c.real("verlet.e_max"), s.w_max = c.real("verlet.w_max");
  s.u = c.reals("verlet.u", n), s.v = c.reals("verlet.v", n), s.a = c.reals("verlet.a", n);
  s.fint = c.reals("verlet.fint", n), s.multipliers = c.reals("verlet.multipliers"), s.history = c.reals("verlet.history");
  if (!c.has("verlet.changes")) return s;  // a model that does not change
  s.stable_time_step = c.real("verlet.stable_time_step"), s.dt_per_stable = c.real("verlet.dt_per_stable");
  s.changed = c.real("verlet.changed"), s.released = c.real("verlet.released");
  s.changing_steps = c.integer("verlet.changing_steps"), s.step_reductions = c.integer("verlet.step_reductions");
  s.changes = c.reals("verlet.changes");
  return s;
}

LoadPathState load_path_state(const Checkpoint& c, std::size_t n, std::size_t history_values) {
  LoadPathState s;
  s.stage = small(c, "load_path.stage"), s.step = small(c, "load_path.step");
  s.iterations = c.integer("load_path.iterations");
  s.residual = c.real("load_path.residual");
  if (c.has("load_path.stiffness_force")) {  // (checkpoints before 2026-12-07 lack them)
    s.residual_force = c.real("load_path.residual_force"), s.stiffness_force = c.real("load_path.stiffness_force");
    s.at_rounding_floor = c.integer("load_path.at_rounding_floor") != 0;
  }
  s.u = c.reals("load_path.u", n), s.u_prev = c.reals("load_path.u_prev", n);
  const auto& value0 = c.reals("load_path.stage_value0");
  std::size_t at = 0;
  for (const std::int64_t size : c.integers("load_path.stage_value0_sizes")) {
    if (size < 0 || std::size_t(size) > value0.size() - at)
      throw InputError(c.source + ": the checkpoint's load_path.stage_value0_sizes do not fit load_path.stage_value0");
    s.stage_value0.emplace_back(value0.begin() + at, value0.begin() + at + size);
    at += std::size_t(size);
  }
  if (at != value0.size())
    throw InputError(c.source + ": the checkpoint's load_path.stage_value0_sizes do not fit load_path.stage_value0");
  const auto& points = c.reals("load_path.plastic");
  const auto& flags = c.integers("load_path.flags");
  if (points.size() != flags.size() * history_values)
    throw InputError(c.source + ": the checkpoint's load_path.plastic does not hold " + std::to_string(history_values) +
                     " values per flag");
  s.plastic = points;
  for (const std::int64_t flag : flags) s.flags.push_back(static_cast<std::uint8_t>(flag != 0));
  s.history = c.reals("load_path.history");
  if (c.has("load_path.changes")) s.changes = c.reals("load_path.changes"), s.carried = c.real("load_path.carried");
  return s;
}

}  // namespace perinom::io

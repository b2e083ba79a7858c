#include "run_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "perinom/core/timer.hpp"
#include "perinom/io/csv_writer.hpp"
#include "diagnostics.hpp"

namespace perinom::cli {

io::Json plastic_summary(const Model& model, const ModelHistory& history) {
  const std::vector<double> xi = history.history_variable();  // (a distributed model's: its owned particles')
  double sums[3] = {0.0, 0.0, double(xi.size())}, extremes[2] = {0.0, -INFINITY};  // max xi, max -xi
  for (const double x : xi) {
    sums[0] += x, sums[1] += x > 0.0;
    extremes[0] = std::max(extremes[0], x), extremes[1] = std::max(extremes[1], -x);
  }
  model.sum_across_ranks(sums, 3);
  model.max_across_ranks(extremes, 2);
  io::Json j = io::Json::object();
  j["particles_yielded"] = static_cast<long long>(sums[1]);
  j["eq_plastic_strain_min"] = sums[2] > 0.0 ? -extremes[1] : 0.0;
  j["eq_plastic_strain_mean"] = sums[2] > 0.0 ? sums[0] / sums[2] : 0.0;
  j["eq_plastic_strain_max"] = extremes[0];
  return j;
}

void write_history(const std::string& path, const History& h) {
  io::CsvWriter csv(path);
  csv.header(h.columns);
  for (std::size_t r = 0; r < h.rows(); ++r) csv.row(h.row(r));
  csv.close();
}

bool TableClock::due() const { return wall_seconds() >= next_; }

void TableClock::wrote(double started) {
  const double now = wall_seconds();
  next_ = now + std::max(kTableSeconds, 50.0 * (now - started));
}

void HistoryAsItGoes::update(const ProgressSample& s) {
  inner_.update(s);
  if (!s.history || s.history->rows() == 0 || !clock_.due()) return;
  const double started = wall_seconds();
  write_history(path_, *s.history);
  clock_.wrote(started);
}

void add_energy_balance(const History& h, io::Json& solver) {
  const std::size_t cols = h.columns.size();
  if (h.rows() == 0 || cols <= 5 || h.columns[5] != "total_energy") return;
  double scale = 0.0;
  for (std::size_t r = 0; r < h.rows(); ++r)
    scale = std::max({scale, std::abs(h.values[r * cols + 4]), h.values[r * cols + 2] + h.values[r * cols + 3]});
  const double defect = std::abs(h.values[(h.rows() - 1) * cols + 5] - h.values[5]);
  const double relative = scale > 0.0 ? defect / scale : 0.0;
  solver["energy_balance"] = relative;
  if (relative > 0.01)
    warn("the energy balance ends off by %.3g%% of the largest work or energy (kinetic + "
                "strain + released - external work; summary.json solver.energy_balance): the dynamics are not "
                "to be trusted (zero-energy modes without stabilization, or too large a time step)",
                100.0 * relative);
}

void add_ramp_reached(double ramp_time, double end_time, io::Json& solver) {
  if (!(ramp_time > 0.0)) return;
  const double s = std::min(1.0, end_time / ramp_time);
  solver["load_factor_at_end"] = s;
  if (s < 1.0)
    warn("the run ended at t = %.4e s, before solver.ramp_time = %.4e s: the loads reached %.1f%% of their values "
         "(the final state and reactions are at that factor; more solver.steps or a shorter ramp_time apply them "
         "whole)",
         end_time, ramp_time, 100.0 * s);
}

}  // namespace perinom::cli

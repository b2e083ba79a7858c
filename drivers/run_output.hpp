#pragma once
// What `perinom run` writes of a solve's history, serial or distributed.
#include <string>
#include <utility>

#include "perinom/core/progress.hpp"
#include "perinom/io/json_writer.hpp"
#include "perinom/models/model.hpp"
#include "perinom/models/model_history.hpp"
#include "perinom/solvers/history.hpp"

namespace perinom::cli {

/// How far the committed plastic strain has spread: particles yielded, xi's range and mean,
/// over the ranks of a distributed model (summary.json `plasticity`).
io::Json plastic_summary(const Model& model, const ModelHistory& history);

/// The history as CSV, one row per recorded iteration or step.
void write_history(const std::string& path, const History& h);

/// When a run rewrites its history files while it goes on: at the first rows, then after
/// kTableSeconds or 50 times the last rewrite's own time, whichever is longer (a table of
/// millions of rows costs at most 2% of the run); whole at the end. A killed run leaves them a
/// few seconds behind.
class TableClock {
 public:
  static constexpr double kTableSeconds = 5.0;
  bool due() const;
  /// Call with wall_seconds() from before the rewrite, right after it.
  void wrote(double started);

 private:
  double next_ = -1e300;
};

/// A progress report that also rewrites the solver's history (ProgressSample::history) to
/// `path` when its TableClock is due, passing every sample on to `inner`.
class HistoryAsItGoes : public Progress {
 public:
  HistoryAsItGoes(Progress& inner, std::string path) : inner_(inner), path_(std::move(path)) {}
  void update(const ProgressSample& s) override;
  void phase(const char* what) override { inner_.phase(what); }
  void warn(const char* what) override { inner_.warn(what); }
  void finish() override { inner_.finish(); }

 private:
  Progress& inner_;
  std::string path_;
  TableClock clock_;
};

/// A Verlet history's energy balance at the end (kinetic + strain + released - work, against
/// the initial energy) over the largest work or energy recorded, as solver["energy_balance"];
/// prints a warning beyond 1%: the solver's guard stops a run only far beyond it
/// (solver.energy_tolerance). A history without energies adds nothing.
void add_energy_balance(const History& h, io::Json& solver);

/// A Verlet run with solver.ramp_time: the loads' factor at its end, min(1, end_time /
/// ramp_time), as solver["load_factor_at_end"]; below 1 a warning says the loads never
/// reached their values (a plate run to 55% of its ramp read 8.0e-5 m against 1.54e-4 m
/// static, with no word).
void add_ramp_reached(double ramp_time, double end_time, io::Json& solver);

}  // namespace perinom::cli

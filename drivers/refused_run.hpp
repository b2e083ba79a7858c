#pragma once
// A `perinom run` refused before its output folder is prepared (reading the scene, its memory,
// a --restart's checkpoint and, for a restart, the particles built): the folder is left as it
// is, unless it holds a finished perinom run (RunFolder::holds_finished_run). Then that run's
// summary.json would pass for this run's (a sweep reading summary.json after each run
// recorded the previous case's "converged" numbers for a --set refused with exit 2): it is
// replaced by an error summary, and nothing else is touched (its snapshots stay, for a typo
// in --set is no reason to lose them; its manifest names them for the next run to remove).
// A --restart refused in the folder it resumes changes nothing there: the run it would
// continue stays whole.
#include <exception>
#include <string>
#include <utility>

#include "perinom/core/error.hpp"

namespace perinom::cli {

class RefusedRun {
 public:
  /// `restart`: the --restart folder ("" without): never recorded into.
  RefusedRun(std::string scene_file, std::string restart)
      : scene_file_(std::move(scene_file)), restart_(std::move(restart)) {}

  /// The output folder once known, and the scene's name ("" before it is read); none when it
  /// is the folder --restart resumes in place (or "").
  void folder(const std::string& dir, std::string name);
  /// From here on nothing is recorded: the folder is the run's (RunFolder records its errors),
  /// or the --restart folder resumed in place.
  void leave_folder() { dir_.clear(); }

  /// Runs `body`; an error it throws before leave_folder() is recorded as above, with the
  /// exit code perinom gives it, and thrown on.
  template <class Body>
  auto recording(Body body) {
    try {
      return body();
    } catch (const InputError& e) {
      record(e.what(), 2);
      throw;
    } catch (const SolveError& e) {
      record(e.what(), 3);
      throw;
    } catch (const std::exception& e) {
      record(e.what(), 4);
      throw;
    }
  }

 private:
  void record(const std::string& error, int exit_code) const;

  std::string scene_file_, restart_, dir_, name_;
};

}  // namespace perinom::cli

#pragma once
// perinom run SCENE --restart DIR: the run resumes from DIR/checkpoint.bin and ends as the
// uninterrupted run would have, bit for bit, if the checkpoint was written for this scene:
// the same keys and values after --set (the `output` section aside, which changes what is
// written, not what is solved), the same solver, the same particles (count, dofs, positions).
//   - The output folder is --out DIR2, or DIR itself (resuming in place).
//   - In place, what the interrupted run wrote after the checkpoint is removed like an
//     earlier run's files, but not the checkpoint nor the snapshots it lists; into another
//     folder those snapshots are copied from DIR, so the .pvd lists the whole series.
#include <set>
#include <string>

#include "perinom/io/checkpoint.hpp"
#include "perinom/scene/problem.hpp"
#include "run_checkpoint.hpp"

namespace perinom::cli {

class Restart {
 public:
  /// Reads DIR/checkpoint.bin and checks its scene and solver, before anything is built.
  /// @throws InputError naming --restart DIR and what does not match (exit code 2).
  Restart(std::string dir, const Scene& scene);

  /// Whether the output folder `out` is DIR itself.
  bool in_place(const std::string& out) const;
  /// The files of DIR that belong to the run resumed: the checkpoint and the snapshots it
  /// lists (.vtu, and .csv where the run wrote them). @throws InputError for a listed file
  /// DIR lacks.
  std::set<std::string> files() const;
  /// Copies files() into `out`, unless in place: the checkpoint too, so that `out` can be
  /// resumed again however the resumed run ends (a run that wrote no later checkpoint left
  /// `out` without one, where the uninterrupted run's folder has one).
  void bring_snapshots(const std::string& out) const;
  /// After the build: the particle and dof counts and the positions are the scene's.
  /// @throws InputError.
  void check(const Problem& p) const;

  const io::Checkpoint& checkpoint() const { return file_; }
  const RunProgress& progress() const { return progress_; }
  /// "DIR/checkpoint.bin (iteration N)", for messages.
  const std::string& where() const { return where_; }

 private:
  std::string dir_, where_;
  io::Checkpoint file_;
  RunProgress progress_;
};

}  // namespace perinom::cli

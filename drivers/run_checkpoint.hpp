#pragma once
// The checkpoints of `perinom run` (output.checkpoint_every): which records a checkpoint.bin
// holds, written from a solver's state and read back into one. The file format is
// io/checkpoint.hpp; resuming a run from one is restart.hpp.
//   what it was written for: scene (Scene::canonical), particles, dofs, positions (a
//     fingerprint of the particles' reference positions), solver (adr, verlet or load_path)
//   the run's progress: snapshot_times, snapshot_files (one name a line), last_snapshot,
//     probe_rows with probe_columns (a load path's point-probe histories)
//   the solver's state, every field of AdrState, VerletState or LoadPathState under its
//     name, prefixed adr., verlet. or load_path. (load_path.plastic: the model's committed
//     history, ModelHistory::values_per_particle() reals a particle: a correspondence model's
//     28, the committed stress, plastic strain, xi and strain or F; stage_value0 flattened
//     with stage_value0_sizes)
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "perinom/io/checkpoint.hpp"
#include "perinom/io/vtk_writer.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/load_path.hpp"
#include "perinom/solvers/verlet.hpp"

namespace perinom::cli {

/// The checkpoint's file name in the output folder.
constexpr const char* checkpoint_name = "checkpoint.bin";

/// What `perinom run` keeps beside a solver's state: the snapshots written so far (the
/// .pvd's entries), the iteration or step of the last one, and a load path's probe rows.
struct RunProgress {
  std::vector<io::PvdSeries::Step> snapshots;
  std::int64_t last_snapshot = -1;
  std::vector<std::vector<double>> probe_rows;
};

/// FNV-1a 64 of the particles' reference positions (their bytes): a mesh or point file
/// changed under the same scene text moves them.
std::uint64_t positions_fingerprint(const Problem& p);

/// "adr", "verlet" or "load_path": the solver state a scene's checkpoints hold.
std::string checkpoint_solver(const Scene& scene);

io::Checkpoint checkpoint_records(const Problem& p, const RunProgress& run, const AdrState& s);
io::Checkpoint checkpoint_records(const Problem& p, const RunProgress& run, const VerletState& s);
io::Checkpoint checkpoint_records(const Problem& p, const RunProgress& run, const LoadPathState& s);

/// The records back; each throws InputError naming a record that is missing or of the
/// wrong size (vectors of the problem's dofs).
RunProgress run_progress(const io::Checkpoint& c);
AdrState adr_state(const io::Checkpoint& c, std::size_t dofs);
VerletState verlet_state(const io::Checkpoint& c, std::size_t dofs);
/// A load path's state; `history_values` is the model's ModelHistory::values_per_particle()
/// (0 for a model without history).
LoadPathState load_path_state(const io::Checkpoint& c, std::size_t dofs, std::size_t history_values);

/// The hook that writes dir/checkpoint.bin every output.checkpoint_every iterations, steps
/// or load steps, with the run's progress as `progress` tells it then.
template <class State>
Checkpoints<State> checkpoint_writer(const std::string& dir, const Problem& p, std::function<RunProgress()> progress) {
  return {p.scene.output.checkpoint_every, [dir, &p, progress](const State& s) {
            io::write_checkpoint(dir + "/" + checkpoint_name, checkpoint_records(p, progress(), s));
          }};
}

}  // namespace perinom::cli

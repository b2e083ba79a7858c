#pragma once
// The checkpoints of `perinom run` (output.checkpoint_every): which records a checkpoint.bin
// holds, written from a solver's state and read back into one. The file format is
// io/checkpoint.hpp; resuming a run from one is restart.hpp.
//   what it was written for: scene (Scene::canonical), particles, dofs, positions (a
//     fingerprint of the particles' reference positions), solver (adr, verlet or load_path)
//   the run's progress: snapshot_times, snapshot_files (one name a line), snapshot_csv (one
//     integer a snapshot: 1 where its .csv was in the folder when the checkpoint was
//     written), last_snapshot,
//     probe_rows with probe_columns (a load path's point-probe histories), stress_path (l2,
//     max: the stress measure's largest norms along the path)
//   the solver's state (io/solver_states.hpp: every field of AdrState, VerletState or
//     LoadPathState under its name, prefixed adr., verlet. or load_path.)
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "perinom/io/checkpoint.hpp"
#include "perinom/io/solver_states.hpp"
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
  /// One flag a snapshot: its .csv was in the folder when the checkpoint was written (per
  /// snapshot, not the scene's output.csv: a resumed run may turn csv on or off, and the
  /// earlier snapshots keep what they had). Empty in checkpoints before 2026-12-07.
  std::vector<std::int64_t> snapshot_csv;
  /// The stress measure's largest norms along the path so far (l2, max; ProbeHistory::stress),
  /// for the damaged Newton check of a resumed run: without them a bar broken before the
  /// checkpoint compared its rounding stresses over rounding. Empty before 2026-12-08.
  std::vector<double> stress_path;
};

/// FNV-1a 64 of the particles' reference positions (their bytes): a mesh or point file
/// changed under the same scene text moves them.
std::uint64_t positions_fingerprint(const Problem& p);

/// FNV-1a 64 of the bytes of the body's files (geometry.mesh, .points, .facets, in that
/// order; 0 for a box): a volume or a facet edited under the same scene text leaves the
/// positions where they were (a point file's volumes times 1.2 resumed a Verlet run with
/// exit 0 to an answer neither file gives).
std::uint64_t body_files_fingerprint(const Scene& scene);

/// "adr", "verlet" or "load_path": the solver state a scene's checkpoints hold.
std::string checkpoint_solver(const Scene& scene);

/// The two fingerprints above, taken once when the run starts: every checkpoint of the run
/// records the files the run was built from, not the files as they are when it is due (a
/// file edited during the run would else resume as if the run had used it; and a mesh is
/// not reread at every checkpoint).
struct RunIdentity {
  std::uint64_t positions = 0, body_files = 0;
};
RunIdentity run_identity(const Problem& p);

/// What the checkpoint was written for and the run's progress (the records above).
io::Checkpoint run_records(const Problem& p, const RunIdentity& id, const RunProgress& run);
/// Those and the solver's state.
template <class State>
io::Checkpoint checkpoint_records(const Problem& p, const RunIdentity& id, const RunProgress& run, const State& s) {
  io::Checkpoint c = run_records(p, id, run);
  io::put_state(c, s);
  return c;
}

/// The run's progress back; throws InputError naming a record that is missing or
/// inconsistent. The solver's state: io::adr_state, io::verlet_state, io::load_path_state.
RunProgress run_progress(const io::Checkpoint& c);

/// The hook that writes dir/checkpoint.bin every output.checkpoint_every iterations, steps
/// or load steps, with the run's progress as `progress` tells it then.
template <class State>
Checkpoints<State> checkpoint_writer(const std::string& dir, const Problem& p, const RunIdentity& id,
                                     std::function<RunProgress()> progress) {
  return {p.scene.output.checkpoint_every, [dir, &p, id, progress](const State& s) {
            io::write_checkpoint(dir + "/" + checkpoint_name, checkpoint_records(p, id, progress(), s));
          }};
}

}  // namespace perinom::cli

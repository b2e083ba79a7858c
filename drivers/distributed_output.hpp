#pragma once
// What a distributed `perinom run` writes of a state (issue 19): each rank its piece of a
// snapshot, rank 0 the .pvtu over the pieces and the .pvd; probe values gathered on rank 0
// from the ranks that own their particles.
#include <string>
#include <vector>

#include "perinom/distributed/distributed_model.hpp"
#include "perinom/io/json_writer.hpp"
#include "perinom/io/vtk_writer.hpp"
#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// A rank's view of the run: the whole cloud's frame (probes bound to it), the local part,
/// the local problem (the local model on subcloud(part)) and the distributed model over it.
struct RankRun {
  const Problem& frame;
  const LocalPart& part;
  const Problem& local;
  const DistributedModel& model;
  int rank = 0, ranks = 1;
};

/// One snapshot at `time`: every rank writes NAME_<index>_<rank>.vtu of its owned particles,
/// rank 0 NAME_<index>.pvtu and the .pvd, and with output.csv NAME_<index>.csv of every
/// particle in the whole cloud's order (the serial run's file, gathered). Every rank calls it. @throws SolveError on every
/// rank, before writing, when a field is NaN or Inf on any.
void add_piece_snapshot(io::PvdSeries& series, double time, const RankRun& run, const std::vector<double>& u,
                        const std::string& dir);

/// The probes' values at the owned state u, as probe_results of a serial run gives them
/// (point probes in the returned object, line probes also in probe_NAME.csv), on rank 0;
/// every rank calls it. @throws SolveError on every rank when a value is NaN or Inf.
io::Json distributed_probe_results(const RankRun& run, const std::vector<double>& u, const std::string& dir);

}  // namespace perinom::cli

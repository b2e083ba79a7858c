#pragma once
// A load path (stages, solver.type adr, lbc or newton) run by `mpirun -np R perinom run` (issue 19):
// the serial solve_load_path on the DistributedModel, with what a serial run prints and
// writes after each load step done over the ranks.
#include <cstdint>
#include <string>
#include <vector>

#include "distributed_output.hpp"
#include "load_path_run.hpp"

namespace perinom::cli {

/// Solves the rank's `stages` (rank_loading's, one per frame stage) into u (the owned dofs)
/// as run_load_path does a serial one: rank 0 prints the step table, every step's point-probe
/// values are gathered into `probes` (rank 0's copy complete), and after the steps
/// output.vtk_steps names (or every output.vtk_every) every rank writes its snapshot piece
/// (last_snapshot: the last step written). Every rank calls it.
SolveReport run_rank_load_path(const RankRun& run, DistributedModel& model, std::vector<LoadStage>& stages,
                               const std::string& dir, std::vector<double>& u, io::PvdSeries& series,
                               ProbeHistory& probes, std::int64_t& last_snapshot);

}  // namespace perinom::cli

#pragma once
// The solve of `perinom run`: the scene's solver on the built problem (solve_problem, the
// solver registry), with its snapshots, its checkpoints (output.checkpoint_every) and, under
// --restart, resumed from a checkpoint.
#include <cstdint>
#include <string>
#include <vector>

#include "perinom/io/vtk_writer.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/registry.hpp"
#include "load_path_run.hpp"
#include "restart.hpp"

namespace perinom::cli {

/// Solves p into u (from rest, or from `restart`'s state when given), adding snapshots to
/// `series` in dir (last_snapshot: the iteration, step or load step of the last one) and,
/// on a load path, the probes' rows to `probes`. A checkpoint that does not fit the
/// problem is an InputError naming it.
SolveReport solve_scene(Problem& p, const std::string& dir, std::vector<double>& u, io::PvdSeries& series,
                        ProbeHistory& probes, std::int64_t& last_snapshot, const Restart* restart);

}  // namespace perinom::cli

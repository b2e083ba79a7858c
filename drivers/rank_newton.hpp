#pragma once
// Newton under `mpirun -np R perinom run` (issue 19): its options on a rank, and the
// `solver.check: newton` of a static solve over the ranks.
#include <vector>

#include "distributed_output.hpp"
#include "perinom/io/json_writer.hpp"
#include "perinom/scene/scene.hpp"
#include "perinom/solvers/newton.hpp"

namespace perinom::cli {

/// Newton's options for a rank: GAMG's rigid-body modes from the owned particles' positions.
NewtonOptions rank_newton_options(const SolverSpec& solver, const RankRun& run);

/// solver.check: newton after a static solve over the ranks: solves `loading` again by Newton
/// over the ranks and reports how far apart the answers are (the whole body's norms, as a
/// serial run's check does; rank 0 prints). Every rank calls it.
io::Json rank_newton_check(const RankRun& run, DistributedModel& model, const Loading& loading,
                           const std::vector<double>& u);

}  // namespace perinom::cli

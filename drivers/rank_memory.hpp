#pragma once
// The memory check of a distributed run (issue 19). The serial estimate (memory_estimate)
// counts the whole scene in one process; under mpirun each rank holds its local part (owned
// particles and ghosts) and, to choose it, the whole cloud. Once a rank's families exist, its
// need is its resident size so far plus the model's measured bytes per bond and per particle
// times its local bonds and particles (the families themselves counted twice: an estimate on
// the high side). Ranks on one host share its memory: their sum must fit what the host has.
#include "perinom/scene/scene.hpp"

namespace perinom::cli {

struct RankMemory {
  double rank_bytes = 0.0;  ///< this rank's estimate
  double most_bytes = 0.0;  ///< the largest rank's
  double host_bytes = 0.0;  ///< the busiest host's sum over its ranks
};

/// Every rank calls it after building its families (`local_bonds`, `local_particles`).
/// Rank 0 prints the estimate; every rank throws the same InputError, naming the key to
/// change, when a rank needs more than `max_memory` (--max-memory bounds each rank) or, with
/// max_memory 0, when a host's ranks need more than its available memory.
RankMemory require_rank_memory(const Scene& scene, double local_bonds, double local_particles, double max_memory);

}  // namespace perinom::cli

#pragma once
/// @file A rank's share of a loading (issue 19).
#include "perinom/models/loading.hpp"
#include "perinom/neighbors/local_part.hpp"

namespace perinom {

/// The part of `whole` (a loading over the whole cloud, d dofs per particle) that acts on the
/// owned particles of `part`, numbered as their dofs are in the DistributedModel: the
/// constraints on them (values, rates, supports, all support names kept, so every rank's
/// reactions line up) and their external forces (pressures' included: small strain, they do
/// not follow the surface, and pressure_force is dropped). `whole` is taken as the frame
/// builds it: its face-located constraints not coupled yet (rank_loading.hpp couples each
/// rank's) and no stage begun (each rank's loading begins its own); otherwise
/// std::invalid_argument.
Loading local_loading(const Loading& whole, const LocalPart& part, int d);

}  // namespace perinom

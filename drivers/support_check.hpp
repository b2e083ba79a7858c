#pragma once
// The warning `perinom run` gives before a static solve whose supports leave the body a
// rigid motion: ADR then drifts along it under any load with a component along it (a crack
// that frees a piece makes one) and stops unbalanced after max_iterations, Newton meets a
// singular tangent; the warning names the motion first.
#include "perinom/geometry/plate_cloud.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/history.hpp"

namespace perinom::cli {

/// For each loading of the run (each stage's, or the scene's): prints a warning (stderr)
/// naming the rigid motions its constraints leave free. Nothing for models whose dofs are not
/// the particles' displacements (plates). Returns whether it warned.
bool warn_if_free(const Problem& p);

/// The same for a distributed run's frame (the whole cloud and loadings, no model; a thin
/// plate's nodes and mirrors in `plate`): the whole body's motions, not its pieces' (those
/// need the whole body's bonds, which no rank holds).
bool warn_if_free_frame(const Problem& frame, const PlateCloud* plate);

/// After a load path with bond breaking stopped unbalanced (its load-step table `steps`,
/// whose last row is the last balanced step): names the pieces the cracks have cut the body
/// into (joined by live bonds; detached particles apart) whose supports in the stage that
/// failed leave them a rigid motion (stdout). Returns whether it named any.
bool explain_free_pieces(const Problem& p, const History& steps);

}  // namespace perinom::cli

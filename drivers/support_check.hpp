#pragma once
// The warning `perinom run` gives before a static solve whose supports leave the body a
// rigid motion: ADR then drifts along it under any load with a component along it (a crack
// that frees a piece makes one) and stops unbalanced after max_iterations, Newton meets a
// singular tangent; the warning names the motion first.
#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// For each loading of the run (each stage's, or the scene's): prints a warning (stderr)
/// naming the rigid motions its constraints leave free. Nothing for models whose dofs are not
/// the particles' displacements (plates). Returns whether it warned.
bool warn_if_free(const Problem& p);

}  // namespace perinom::cli

#pragma once
// constraints: rigid_body's checks in a distributed run (issue 19), made as a serial run
// makes them (problem.cpp): the body is in one piece (its pins hold one piece only), and the
// loads the run applies are balanced. The frame has no bonds and, for the consistent
// formulation, not its loads (the trace's face loads; the frame's outer-layer loads of a
// balanced shear have a moment tau dx (L - h)): the ranks check what they hold.
#include <vector>

#include "perinom/neighbors/families.hpp"
#include "perinom/neighbors/local_part.hpp"
#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// Every rank calls it, with its part, its families, its local cloud and its loadings (the
/// scene's and each stage's, rank_loading's); every rank throws the same InputError, the
/// serial run's, for a body in pieces or (the consistent formulation) unbalanced loads.
void require_rigid_body_over_ranks(const Problem& frame, const LocalPart& part, const Families& families,
                                   const PointCloud& local_cloud, const Loading& loading,
                                   const std::vector<LoadStage>& stages);

}  // namespace perinom::cli

#pragma once
/// @file A distributed rank's loading from its scene (issue 19).
#include "perinom/distributed/local_facets.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/neighbors/local_part.hpp"
#include "perinom/scene/problem.hpp"

namespace perinom {

/// The loading of `part`'s owned particles (`local_cloud`: the part's particles, its model's)
/// for the boundary items `boundary` (the scene's, or a load stage's: stage_boundary), whose
/// loading on the whole cloud is `whole` (frame.loading or a frame stage's, with `frame`
/// build_problem_frame's): its constraints and forces on the owned dofs (local_loading),
/// with the face-located constraints (`at: face`) coupled as a serial run couples them,
/// through the part's model `local` (whose owned rows of G and of the trace are the whole
/// body's) and `facets` (the part's share of frame.facets and frame.groups, the trace's
/// facets when it has one), and exchanging over `ranks`, which must outlive the loading. Its
/// forces are whole's, or, with a trace (the consistent formulation), the trace's
/// work-consistent facet loads.
Loading rank_loading(const Scene& scene, const std::vector<BoundarySpec>& boundary, const Loading& whole,
                     const Problem& frame, const LocalPart& part, const PointCloud& local_cloud,
                     const CorrespondenceModel& local, const LocalFacets& facets, const LoadingRanks& ranks);

}  // namespace perinom

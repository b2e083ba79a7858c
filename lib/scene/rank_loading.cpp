#include "perinom/scene/rank_loading.hpp"

#include <algorithm>

#include "perinom/distributed/local_loading.hpp"
#include "scene_loading.hpp"

namespace perinom {

Loading rank_loading(const Scene& s, const std::vector<BoundarySpec>& boundary, const Loading& whole, const Problem& frame,
                     const LocalPart& part, const PointCloud& local_cloud, const CorrespondenceModel& local,
                     const LocalFacets& facets, const LoadingRanks& ranks) {
  const int d = frame.cloud.dim;
  Loading mine = local_loading(whole, part, d);
  const BoundaryTrace& trace = local.trace();
  if (!trace.empty() && !mine.force.empty()) {
    // The consistent formulation's tractions act at the facets through the trace: each owned
    // particle's share (facets of near ghosts reach owned particles too).
    const std::vector<double> f = detail::trace_forces(s, boundary, trace, facets.groups, local_cloud.size());
    std::copy(f.begin(), f.begin() + std::ptrdiff_t(part.owned * d), mine.force.begin());
  }
  // Which constraints are face-located, by their dofs in the whole cloud (the frame keeps
  // only its loading): the same selection again, O(N).
  detail::FaceOf whole_faces;
  detail::make_loading(s, boundary, frame.cloud, whole_faces, detail::BoundaryData{&frame.facets, &frame.groups, nullptr});
  if (whole_faces.empty()) return mine;
  // Every rank couples (a rank without face constraints too): the exchanges are collective.
  const auto owned = owned_index(part);
  detail::FaceOf faces;
  for (auto [dof, face] : whole_faces) {
    const auto at = owned.find(ParticleId(dof / d));
    if (at == owned.end()) continue;
    if (face.facet >= 0) face.facet = facets.local_of[std::size_t(face.facet)];  // an owned particle's: local
    faces[std::int64_t(at->second) * d + dof % d] = face;
  }
  const detail::BoundaryData data{trace.empty() ? &facets.facets : &trace.facets(), &facets.groups, &trace};
  detail::couple_to_faces(mine, faces, s.geometry, local_cloud, local.G(), data);
  mine.ranks = &ranks;
  return mine;
}

}  // namespace perinom

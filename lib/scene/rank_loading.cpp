#include "perinom/scene/rank_loading.hpp"

#include "perinom/distributed/local_loading.hpp"
#include "scene_loading.hpp"

namespace perinom {

Loading rank_loading(const Scene& s, const Problem& frame, const LocalPart& part, const PointCloud& local_cloud,
                     const CorrespondenceModel& local, const LoadingRanks& ranks) {
  const int d = frame.cloud.dim;
  // Which constraints are face-located, by their dofs in the whole cloud (the frame keeps
  // only its loading): the same selection again, O(N).
  detail::FaceOf whole_faces;
  detail::make_loading(s, s.boundary, frame.cloud, whole_faces, detail::BoundaryData{nullptr, &frame.groups, nullptr});
  Loading mine = local_loading(frame.loading, part, d);
  if (whole_faces.empty()) return mine;
  // Every rank couples (a rank without face constraints too): the exchanges are collective.
  const auto owned = owned_index(part);
  detail::FaceOf faces;
  for (const auto& [dof, face] : whole_faces) {
    const auto at = owned.find(ParticleId(dof / d));
    if (at != owned.end()) faces[std::int64_t(at->second) * d + dof % d] = face;
  }
  const BoundaryTrace& trace = local.trace();
  const detail::BoundaryData data{trace.empty() ? nullptr : &trace.facets(), nullptr, &trace};
  detail::couple_to_faces(mine, faces, s.geometry, local_cloud, local.G(), data);
  mine.ranks = &ranks;
  return mine;
}

}  // namespace perinom

#include "rank_rigid_body.hpp"

#include "perinom/distributed/ranks.hpp"
#include "perinom/distributed/whole_pieces.hpp"

namespace perinom::cli {

void require_rigid_body_over_ranks(const Problem& frame, const LocalPart& part, const Families& families,
                                   const PointCloud& local_cloud, const Loading& loading,
                                   const std::vector<LoadStage>& stages) {
  const Scene& s = frame.scene;
  if (s.constraints != "rigid_body") return;
  const WholePieces pieces = whole_pieces(part, families, frame.cloud.size());
  if (pieces.count > 1) throw InputErrorOnEveryRank(rigid_body_pieces_error(s, pieces.count, pieces.second).what());
  if (s.model.formulation != "consistent") return;  // the frame checked its loads, the ranks' own
  // Each rank's share about the whole cloud's centroid, summed: the serial run's resultants
  // to rounding, alike on every rank.
  const LoadResultant whole = load_resultant(frame.cloud, {});
  std::vector<LoadResultant> resultants;
  std::vector<const Loading*> loadings = {&loading};
  for (const auto& st : stages) loadings.push_back(&st.loading);
  for (const Loading* load : loadings) {
    LoadResultant r = load_resultant_part(local_cloud, load->force, load->force.empty() ? 0 : part.owned, whole);
    double sums[7] = {r.force[0], r.force[1], r.force[2], r.moment[0], r.moment[1], r.moment[2], r.force_scale};
    sum_over_ranks(sums, 7);
    r.force = {sums[0], sums[1], sums[2]}, r.moment = {sums[3], sums[4], sums[5]}, r.force_scale = sums[6];
    resultants.push_back(r);
  }
  try {
    require_balanced_loads(frame, resultants, false);
  } catch (const InputError& e) {
    throw InputErrorOnEveryRank(e.what());
  }
}

}  // namespace perinom::cli

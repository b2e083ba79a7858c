#pragma once
// Boundary conditions turned into a Loading: the particles and facets each boundary item
// selects (box sides, boxes, facet groups), the forces of its tractions and pressures, and
// the couplings of face-located constraints.
#include <cstdint>
#include <map>
#include <vector>

#include "perinom/geometry/body.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/operators/boundary_trace.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
#include "perinom/scene/scene.hpp"

namespace perinom::detail {

/// Where each face-located constraint acts: a facet (facet >= 0: its centroid, a group's
/// facet or, with a trace, the facet of the particle's lattice cell on that side), or the
/// face of a box side (axis -1: on the particle).
struct FaceRef {
  Side side;
  std::int64_t facet = -1;
};
using FaceOf = std::map<std::int64_t, FaceRef>;

/// The body's boundary as the loading sees it: the facets (the trace's when there is one)
/// and their named groups.
struct BoundaryData {
  const BoundaryFacets* facets = nullptr;
  const std::vector<FacetGroup>* groups = nullptr;
  const BoundaryTrace* trace = nullptr;
};

/// The particles a side, box or point region of the scene selects; InputError naming `where`
/// (e.g. "file:line: boundary[0]") when it selects none or its point lies off the body.
std::vector<ParticleId> select_region(const Region& region, const Scene& s, const PointCloud& cloud,
                                      const std::string& where);

/// The constraints and forces of a boundary list; face-located constraints are recorded in
/// face_of for couple_to_faces. Throws InputError naming the item for a region that selects
/// nothing or an unknown group.
Loading make_loading(const Scene& s, const std::vector<BoundarySpec>& boundary, const PointCloud& cloud,
                     FaceOf& face_of, const BoundaryData& data);

/// The nodal forces (particles x d) of the tractions and pressures in `boundary` (small
/// strain: they do not follow the surface), on box sides or on `groups` (facet indices into
/// the trace's facets), through `trace`: the consistent formulation's work-consistent facet
/// loads, as its loading has them, on whatever cloud the trace was built on (a distributed
/// rank's local part, whose groups may be empty there).
std::vector<double> trace_forces(const Scene& s, const std::vector<BoundarySpec>& boundary, const BoundaryTrace& trace,
                                 const std::vector<FacetGroup>& groups, std::size_t particles);

/// Face-located constraints: u_i + (grad u)_i . r = u_bar with r from the particle to the point
/// on its face, i.e. u_i (1 - sum_j c_j) + sum_j c_j u_j = u_bar with c_j = g_ij . r. With a trace
/// (the consistent formulation) the point is the centroid of the particle's facet (on that side,
/// or in that group) and the row is the trace's own, so the constraint reacts exactly where a
/// facet load acts. Without one, a group's constraint acts at its facet's centroid and a side's
/// on the box face along the side's axis.
void couple_to_faces(Loading& load, const FaceOf& face_of, const BoxGeometry& box, const PointCloud& cloud,
                     const NonlocalOperator& G, const BoundaryData& data);

}  // namespace perinom::detail

#pragma once
/// @file A rank's share of the body's boundary facets and facet groups (issue 19).
#include <cstdint>
#include <vector>

#include "perinom/geometry/body.hpp"
#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/neighbors/local_part.hpp"

namespace perinom {

/// The facets of the first `rows` local particles of `part` (its owned and near ones: the
/// rows it evaluates), their particles numbered locally, and every group with its facets
/// renumbered into that list (a group whose facets all lie elsewhere is kept, empty, so its
/// name still resolves on every rank).
struct LocalFacets {
  BoundaryFacets facets;
  std::vector<FacetGroup> groups;
  /// For each facet of the whole body: its index in `facets`, or -1 when it is not local.
  std::vector<std::int64_t> local_of;
};

LocalFacets local_facets(const BoundaryFacets& whole, const std::vector<FacetGroup>& groups, const LocalPart& part,
                         std::size_t rows);

}  // namespace perinom

#pragma once
/// @file A body given by particles and, when known, its boundary facets in named groups:
/// what a mesh (mesh_body.hpp) or a point file (point_file.hpp) becomes, where a box
/// becomes a lattice.
#include <cstddef>
#include <string>
#include <vector>

#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/geometry/point_cloud.hpp"

namespace perinom {

/// A named part of the boundary: the indices of its facets (into Body::facets), ascending.
/// A facet may belong to several groups.
struct FacetGroup {
  std::string name;
  std::vector<std::size_t> facets;
};

/// Particles, facets (empty when the source has none) and the facet groups.
struct Body {
  PointCloud cloud;
  BoundaryFacets facets;
  std::vector<FacetGroup> groups;
  std::size_t elements = 0;  ///< mesh elements the particles come from (0: not a mesh)
  double mean_size = 0.0;    ///< (mean particle volume, per unit thickness in 2-D)^(1/dim) (m)
};

/// The group of that name, or nullptr.
const FacetGroup* find_group(const std::vector<FacetGroup>& groups, const std::string& name);

/// The particles that own a facet of the group, ascending, each once.
std::vector<ParticleId> group_particles(const FacetGroup& group, const BoundaryFacets& facets);

/// Sets the cloud's mean_size-derived fields: cloud.spacing (mean_size on every axis, which
/// line probes use as the particle spacing) and body.mean_size, from the volumes.
void set_mean_size(Body& body, double thickness);

}  // namespace perinom

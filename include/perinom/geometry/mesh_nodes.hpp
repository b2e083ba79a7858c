#pragma once
/// @file Checks on the nodes a body takes from a mesh: those its elements use, in a plane
/// for a 2-D body, and no two at one point (an unmerged seam).
#include <cstddef>
#include <vector>

#include "perinom/geometry/gmsh_mesh.hpp"

namespace perinom {

/// The nodes (indices into the mesh's node rows) that the elements of dimension dim use,
/// ascending, each once. Nodes used by no such element (the geometry's construction points,
/// the nodes of lower-dimensional elements only) are not part of the body.
std::vector<std::size_t> used_nodes(const GmshMesh& mesh, int dim);

/// Throws InputError (without a key) when the nodes' z is not constant to 1e-12 of their
/// extent: a 2-D body is a mesh in a plane z = const.
void check_planar(const GmshMesh& mesh, const std::vector<std::size_t>& nodes);

/// Throws InputError (without a key) naming two nodes, by gmsh tag, that lie within
/// 1e-8 of the nodes' bounding-box diagonal of each other (gmsh's own Geometry.Tolerance,
/// the distance its Coherence merges nodes within). Elements that meet at such a pair
/// share no face: each keeps its side as a boundary facet, an internal seam that the
/// divergence theorem does not see (the two sides' facets cancel) but the consistent
/// formulation takes for a free crack. Found in O(N) with a hash grid of that cell size.
void check_distinct_nodes(const GmshMesh& mesh, const std::vector<std::size_t>& nodes);

}  // namespace perinom

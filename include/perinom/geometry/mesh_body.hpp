#pragma once
/// @file Body-fitted particles: one particle per element of a mesh, the mesh's boundary
/// faces as the body's facets (the approach of Peridigm and PeriLab for the particles).
#include "perinom/geometry/body.hpp"
#include "perinom/geometry/gmsh_mesh.hpp"

namespace perinom {

/// The body of a mesh in dim = 2 or 3 dimensions.
/// - Particles: one per element of dimension dim (2-D: triangles and quadrangles, the mesh
///   in a plane z = const; 3-D: tetrahedra, hexahedra, prisms, pyramids), in the order of
///   the file, at the element's centroid with its exact volume (2-D: area times thickness).
///   Lower-dimensional elements only name boundary groups.
/// - Facets: every face (2-D: edge) that belongs to one element only, owned by that
///   element's particle, with its exact area (2-D: length times thickness), unit outward
///   normal and centroid. A quadrangular face of a 3-D element is split into two triangles
///   along the diagonal through its node of smallest tag (both neighbours split it alike);
///   the element's volume and centroid are those of the polyhedron so bounded, and a
///   planar face (the two normals within 1e-12) stays one facet. So the facets close the
///   body exactly: sum_k A_k n_k (x) y_k = (sum_i V_i) I to rounding.
/// - Groups: the physical groups of dimension dim - 1 (gmsh Physical Curve in 2-D,
///   Physical Surface in 3-D), named as in the file (an unnamed group by its tag); a boundary
///   facet belongs to the groups of the mesh element lying on its face. Facet side codes are
///   100 + the index of its first group (BoundaryFacets::side), or -1 outside every group.
/// Throws InputError (without a key) for a mesh with no element of dimension dim, a
/// degenerate element, a face shared by more than two elements, a 2-D mesh off a plane, or
/// two of its nodes at one point (mesh_nodes.hpp).
Body mesh_body(const GmshMesh& mesh, int dim, double thickness);

}  // namespace perinom

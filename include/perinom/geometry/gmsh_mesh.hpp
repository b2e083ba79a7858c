#pragma once
/// @file A gmsh mesh as read from a .msh file (format 4.1, ASCII): nodes, first-order
/// elements and the physical groups of their entities. No dependency on gmsh itself.
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace perinom {

/// A physical group: gmsh's (dimension, tag) and its name ("" when the file gives none).
struct GmshGroup {
  int dim = 0;
  int tag = 0;
  std::string name;
};

/// The elements of every dimension, in the order of the file. Element e has gmsh type
/// type[e] (1 line, 2 triangle, 3 quadrangle, 4 tetrahedron, 5 hexahedron, 6 prism,
/// 7 pyramid, 15 point), lies on the entity (dim[e], entity[e]), and its nodes are
/// node_index[offsets[e] .. offsets[e+1]) in gmsh's local order, as indices into the
/// node rows (not gmsh tags).
struct GmshMesh {
  std::vector<double> x;            ///< 3 coordinates per node (m), node-major
  std::vector<std::size_t> tag;     ///< gmsh's tag of each node (for tie-breaks and messages)
  std::vector<int> type, dim, entity;
  std::vector<std::size_t> offsets{0};
  std::vector<std::size_t> node_index;
  std::vector<GmshGroup> groups;
  /// The physical tags of each entity (dim, tag) that has any.
  std::map<std::pair<int, int>, std::vector<int>> entity_groups;

  std::size_t nodes() const { return tag.size(); }
  std::size_t elements() const { return type.size(); }
};

/// Dimension (0-3) and node count of a first-order gmsh element type, or {-1, 0} for any
/// other type (higher-order ones included).
std::pair<int, int> gmsh_element_shape(int type);

/// Reads a .msh file of format 4.1, ASCII. Throws InputError ("line N: ...", without the
/// path) for a file that cannot be read, another version, the binary form, a partitioned
/// mesh, an element type other than the first-order ones above (higher-order meshes are
/// refused: mesh with Mesh.ElementOrder = 1), or an element that lists a node twice (a
/// collapsed element, named by its gmsh tag).
GmshMesh read_gmsh(const std::string& path);

}  // namespace perinom

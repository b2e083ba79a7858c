#pragma once
/// @file The particles of a rectangular thin plate: a vertex lattice (nodes on the edges) and
/// mirror ghosts across its supported edges (THEORY sec. 7).
#include <array>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/lattice.hpp"

namespace perinom {

/// How an edge of the plate is held. simply_supported: w = 0 on the edge, and the ghosts
/// outside it mirror w with the opposite sign (w odd across the edge, so w'' = 0 there);
/// clamped: w = 0 on the edge and the ghosts mirror w with the same sign (w even, so
/// dw/dn = 0 there); free: no ghosts, the fits near the edge are one-sided.
enum class EdgeSupport { free, simply_supported, clamped };

/// Edges in the order xmin, xmax, ymin, ymax (Side axis * 2 + at_max).
using PlateEdges = std::array<EdgeSupport, 4>;

/// A vertex lattice of the box [min, max] (2-D): round(L / dx) cells per axis and a node at
/// every cell corner, so the edge nodes lie on the edges (the simply supported condition sits
/// where it belongs, not half a spacing inside). Ghost nodes are the mirror images of the
/// nodes within `layers` spacings of a supported edge (and, at a corner between two supported
/// edges, the images through both); w at a ghost is sign * w at its image. The ghosts carry no
/// energy: they only complete the families of the nodes near the edge.
struct PlateCloud {
  /// Physical nodes first (x fastest, then y), then the ghosts. cloud.volume is the cell
  /// volume dx dy t for every node (the weights V_j of the fits).
  PointCloud cloud;
  std::size_t physical = 0;
  std::array<long, 2> nodes{0, 0};  ///< physical nodes per axis
  std::vector<ParticleId> image;    ///< per ghost: the physical node it mirrors
  std::vector<double> sign;         ///< per ghost: w_ghost = sign * w_image
  std::vector<double> area;         ///< per physical node: its quadrature area (m^2), trapezoid rule

  /// The physical nodes on edge e (0 xmin, 1 xmax, 2 ymin, 3 ymax), corners included.
  std::vector<ParticleId> edge_nodes(int e) const;
};

/// Builds the plate's nodes and ghosts. Throws InputError when a side is shorter than two
/// cells or the lattice exceeds the particle limit.
PlateCloud make_plate_cloud(const BoxGeometry& box, double dx, const PlateEdges& edges, int layers);

/// The listed physical nodes of `whole` (distinct) as a plate of their own, in that order,
/// then the ghosts of `whole` that mirror one of them (in whole's order, their images
/// renumbered): a distributed rank's local plate. Its `nodes` are zero (edge_nodes is the
/// whole plate's alone).
PlateCloud sub_plate(const PlateCloud& whole, const std::vector<ParticleId>& nodes);

}  // namespace perinom

#pragma once
/// @file Neighbour search: fixed radius (cell list, O(N)) and k nearest (k-d tree, O(N log N)).
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/families.hpp"

namespace perinom {

/// The relative slack on delta^2 within which a neighbour counts as at the horizon (a
/// lattice neighbour at exactly 3 dx with horizon ratio 3.0 is in the family whatever the
/// rounding of its coordinates).
inline constexpr double kHorizonTie = 1e-9;

/// Families of all j != i with |x_j - x_i|^2 <= delta^2 (1 + kHorizonTie) (a uniform cell
/// list of cell size delta (1 + kHorizonTie)).
Families radius_families(const PointCloud& cloud, double delta);

/// Families of the k nearest neighbours of each particle (nanoflann k-d tree).
/// support[i] is the distance to the k-th neighbour. Ties at the k-th distance are broken
/// by the tree; the result is a valid k-nearest set either way.
Families knn_families(const PointCloud& cloud, int k);

}  // namespace perinom

#pragma once
/// @file Per-bond scalar weights w_ij V_j and the shape tensors K_i (THEORY sec. 2).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/families.hpp"
#include "perinom/operators/influence.hpp"

namespace perinom {

/// Scalar bond data shared by every first-order operator.
/// wv[k] = w_ij V_j for bond k = (i, j); shape[i*d*d ..] = K_i = sum_j w_ij V_j xi (x) xi
/// (row-major d x d); shape_inverse likewise holds K_i^-1.
struct BondWeights {
  std::vector<double> wv;
  std::vector<double> shape;
  std::vector<double> shape_inverse;
};

/// Computes the weights and shape tensors; throws InputError naming the first particle whose
/// shape tensor is singular (its family does not span R^d), with its position and family size.
/// Particles from `checked_rows` on are not checked (a distributed rank's far ghosts, whose
/// truncated families no row reads: OperatorOptions::fitted_rows).
BondWeights bond_weights(const PointCloud& cloud, const Families& families, Influence kind,
                         std::size_t checked_rows = SIZE_MAX);

}  // namespace perinom

#pragma once
/// @file What the fracture criteria measure on each bond of the graph (THEORY sec. 10): one
/// value per bond slot in row order, 0 for a dead bond; and the damage of each particle.
#include <cmath>
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/bond_graph.hpp"
#include "perinom/operators/hourglass_energy.hpp"

namespace perinom {

/// The stretch (|xi + eta| - |xi|) / |xi| of bond (i, j), eta = u_j - u_i.
struct BondStretch {
  int d;
  const double* x;  ///< positions, N x d
  const double* u;  ///< displacements, N x d
  double operator()(std::size_t i, std::size_t j) const {
    double l2 = 0.0, y2 = 0.0;
    for (int a = 0; a < d; ++a) {
      const double xi = x[j * d + a] - x[i * d + a];
      const double y = xi + u[j * d + a] - u[i * d + a];
      l2 += xi * xi, y2 += y * y;
    }
    const double l = std::sqrt(l2);
    return (std::sqrt(y2) - l) / l;
  }
};

/// The hourglass strain |z_ij| / |xi_ij| of bond (i, j), z_ij = u_j - u_i - H_i xi_ij.
struct HourglassStrain {
  int d;
  const double* x;  ///< positions, N x d
  const double* u;  ///< displacements, N x d
  const double* H;  ///< grad u, N x d x d
  double operator()(std::size_t i, std::size_t j) const {
    double l2;
    const double z2 = hourglass_z2(d, x, u, H, i, j, l2);
    return std::sqrt(z2 / l2);
  }
};

/// The hourglass strain |z_ij| / |xi_ij| of every live bond (i, j), z_ij = u_j - u_i -
/// H_i xi_ij, xi_ij = x_j - x_i, for u (N x d) and H = grad u (N x d x d, from the model's G):
/// the part of the relative displacement the gradient does not explain (zero for any affine
/// u when G is exact for linear fields).
void hourglass_strains(const PointCloud& cloud, const BondGraph& graph, const double* u, const double* H,
                       std::vector<double>& s);

/// The stretch (|xi + eta| - |xi|) / |xi| of every live bond, eta = u_j - u_i.
void bond_stretches(const PointCloud& cloud, const BondGraph& graph, const double* u, std::vector<double>& s);

/// The bond stress (sigma1_i + sigma1_j) / 2 of every live bond, sigma1 the largest principal
/// stress per particle (seed 000 eq. 49-51).
void bond_stresses(const BondGraph& graph, const std::vector<double>& sigma1, std::vector<double>& t);

/// d_i = sum of V_j over the dead bonds of row i / sum of V_j over all its bonds (seed 002
/// eq. 88, volume-weighted); 0 for an empty family.
std::vector<double> damage(const BondGraph& graph, const std::vector<double>& volume);

}  // namespace perinom

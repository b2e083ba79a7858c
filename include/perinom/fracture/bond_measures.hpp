#pragma once
/// @file What the fracture criteria measure on each bond of the graph (THEORY sec. 10): one
/// value per bond slot in row order, 0 for a dead bond; and the damage of each particle.
#include <cmath>
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/bond_graph.hpp"
#include "perinom/operators/hourglass_energy.hpp"

namespace perinom {

/// The stretch (|xi + eta| - |xi|) / |xi| of bond (i, j), eta = u_j - u_i. Dim: int, or
/// std::integral_constant<int, D> for bond loops the compiler unrolls (the criteria's pass).
template <class Dim = int>
struct BondStretch {
  Dim d;
  const double* x;  ///< positions, N x d
  const double* u;  ///< displacements, N x d
  double operator()(std::size_t i, std::size_t j) const {
    double l2, y2;
    lengths2(i, j, l2, y2);
    const double l = std::sqrt(l2);
    return (std::sqrt(y2) - l) / l;
  }
  /// (|xi + eta| / |xi|)^2, whose root minus one is the stretch: no root per bond.
  double squared_ratio(std::size_t i, std::size_t j) const {
    double l2, y2;
    lengths2(i, j, l2, y2);
    return y2 / l2;
  }
  /// The stretch above s (> -1), without a root or a division: |xi + eta|^2 > (1 + s)^2 |xi|^2.
  bool exceeds(std::size_t i, std::size_t j, double s) const {
    double l2, y2;
    lengths2(i, j, l2, y2);
    return y2 > (1.0 + s) * (1.0 + s) * l2;
  }

 private:
  void lengths2(std::size_t i, std::size_t j, double& l2, double& y2) const {
    l2 = 0.0, y2 = 0.0;
    for (int a = 0; a < d; ++a) {
      const double xi = x[j * d + a] - x[i * d + a];
      const double y = xi + u[j * d + a] - u[i * d + a];
      l2 += xi * xi, y2 += y * y;
    }
  }
};

/// The hourglass strain |z_ij| / |xi_ij| of bond (i, j), z_ij = u_j - u_i - H_i xi_ij (Dim
/// as for BondStretch).
template <class Dim = int>
struct HourglassStrain {
  Dim d;
  const double* x;  ///< positions, N x d
  const double* u;  ///< displacements, N x d
  const double* H;  ///< grad u, N x d x d
  double operator()(std::size_t i, std::size_t j) const {
    double l2;
    const double z2 = hourglass_z2(d, x, u, H, i, j, l2);
    return std::sqrt(z2 / l2);
  }
  /// Its square |z_ij|^2 / |xi_ij|^2: no root per bond.
  double squared(std::size_t i, std::size_t j) const {
    double l2;
    const double z2 = hourglass_z2(d, x, u, H, i, j, l2);
    return z2 / l2;
  }
  /// The hourglass strain above t >= 0, without a root or a division: |z|^2 > t^2 |xi|^2.
  bool exceeds(std::size_t i, std::size_t j, double t) const {
    double l2;
    return hourglass_z2(d, x, u, H, i, j, l2) > t * t * l2;
  }
};
template <class Dim>
BondStretch(Dim, const double*, const double*) -> BondStretch<Dim>;
template <class Dim>
HourglassStrain(Dim, const double*, const double*, const double*) -> HourglassStrain<Dim>;

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

/// The first break event of each particle (BondGraph::event): the smallest event among the
/// bonds of row i that a run broke, 0 when none (bonds cut at build time have event 0). Coloured
/// by it, a crack shows the order it grew in, from the precracks' tips too.
std::vector<double> first_break_event(const BondGraph& graph);

}  // namespace perinom

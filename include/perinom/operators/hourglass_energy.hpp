#pragma once
/// @file The first-order stabilization's energy at each particle (THEORY sec. 4): what the
/// VTK field `hourglass_energy_density` shows, where the zero-energy modes are held.
#include <cstddef>
#include <type_traits>
#include <vector>

#include "perinom/operators/nonlocal_operator.hpp"

namespace perinom {

/// z_ij = u_j - u_i - H_i xi_ij into z (d values), xi_ij = x_j - x_i, and |xi_ij|^2 into l2:
/// the one bond formula behind the hourglass energy, its force and the fracture criterion's
/// hourglass strain (positions and u N x d, H N x d x d). Dim: int, or
/// std::integral_constant<int, D> for loops the compiler unrolls.
template <class Dim>
inline void hourglass_z(Dim d, const double* x, const double* u, const double* H, std::size_t i, std::size_t j,
                        double* z, double& l2) {
  double xi[3];
  l2 = 0.0;
  for (int b = 0; b < d; ++b) xi[b] = x[j * d + b] - x[i * d + b], l2 += xi[b] * xi[b];
  for (int a = 0; a < d; ++a) {
    z[a] = u[j * d + a] - u[i * d + a];
    for (int b = 0; b < d; ++b) z[a] -= H[(i * d + a) * d + b] * xi[b];
  }
}
/// |z_ij|^2 (hourglass_z), and |xi_ij|^2 into l2.
template <class Dim>
inline double hourglass_z2(Dim d, const double* x, const double* u, const double* H, std::size_t i, std::size_t j,
                           double& l2) {
  double z[3], z2 = 0.0;
  hourglass_z(d, x, u, H, i, j, z, l2);
  for (int a = 0; a < d; ++a) z2 += z[a] * z[a];
  return z2;
}

/// psi_i = 1/2 (modulus / tr K_i) sum_j w_ij V_j |z_ij|^2 (J/m^3) over the live bonds, with
/// z_ij = u_j - u_i - H_i xi_ij and H = grad u from G (first order, built from a fit: its
/// positions and w V); 0 at a detached particle. sum_i V_i psi_i is the energy W_s of the
/// first-order stabilization S0 with c_i = modulus / tr K_i (stabilization.hpp).
/// Throws std::invalid_argument for G of order 2 or without its fit's inputs.
std::vector<double> hourglass_energy_density(const NonlocalOperator& G, const double* u, double modulus);
/// Row i's share of W_s, psi_i above (J/m^3), for u and H = grad u (N x d x d, row i read).
/// With f (N x d): also f += sign V_i d psi_i / du, that row's share of S u: c_i V_i w_ij V_j
/// z_ij at j and minus their sum at i, c_i = modulus / tr K_i (the path through H_i adds
/// nothing: fused_stabilization.hpp). 0 and nothing added at a detached particle. What a
/// model updates on the rows that breaks refresh, instead of a whole product.
double hourglass_row(const NonlocalOperator& G, const double* u, const double* H, std::size_t i, double modulus,
                     double volume, double sign, double* f);

}  // namespace perinom

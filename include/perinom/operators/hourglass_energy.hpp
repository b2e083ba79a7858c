#pragma once
/// @file The first-order stabilization's energy at each particle (THEORY sec. 4): what the
/// VTK field `hourglass_energy_density` shows, where the zero-energy modes are held.
#include <vector>

#include "perinom/operators/nonlocal_operator.hpp"

namespace perinom {

/// psi_i = 1/2 (modulus / tr K_i) sum_j w_ij V_j |z_ij|^2 (J/m^3) over the live bonds, with
/// z_ij = u_j - u_i - H_i xi_ij and H = grad u from G (first order, built from a fit: its
/// positions and w V); 0 at a detached particle. sum_i V_i psi_i is the energy W_s of the
/// first-order stabilization S0 with c_i = modulus / tr K_i (stabilization.hpp).
/// Throws std::invalid_argument for G of order 2 or without its fit's inputs.
std::vector<double> hourglass_energy_density(const NonlocalOperator& G, const double* u, double modulus);

}  // namespace perinom

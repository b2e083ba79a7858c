#pragma once
/// @file The zero-energy-mode stabilization S = Z^T W Z (THEORY sec. 4).
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/families.hpp"
#include "perinom/operators/bond_weights.hpp"
#include "perinom/operators/gradient_operator.hpp"
#include "perinom/operators/scalar_csr.hpp"

namespace perinom {

/// Assembles the scalar matrix S0 of W_s = 1/2 sum_i V_i c_i sum_j w_ij V_j |z_ij|^2,
/// z_ij = u_j - u_i - (grad u)_i xi_ij, so that f_s = (S0 (x) I_d) u.
/// Uses the closed form of particle i's local block (no bond-by-bond outer products):
///   M_i = c_i V_i (D_i - A_i K_i^-1 A_i^T),
/// D_i = sum_j w_ij V_j (e_j - e_i)(e_j - e_i)^T, A_i rows a_ij = w_ij V_j xi_ij and
/// -sum_j a_ij for i itself (A_i K_i^-1 rows are the weights of G). S0 is symmetric,
/// positive semi-definite and zero on linear fields. coefficient[i] = c_i in Pa/m^5
/// (see stabilization_coefficients).
ScalarCsr assemble_stabilization(const PointCloud& cloud, const Families& families,
                                 const BondWeights& weights, const GradientOperator& G,
                                 const std::vector<double>& coefficient);

/// c_i = C_hg * 2 mu / tr(K_i) for every particle.
std::vector<double> stabilization_coefficients(const BondWeights& weights, int dim, double c_hg,
                                               double mu);

}  // namespace perinom

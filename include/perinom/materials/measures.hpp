#pragma once
/// @file Scalar measures of a stress or a displacement gradient, for output and probes.

namespace perinom {

/// Mean stress tr(sigma) / 3 of a 3 x 3 stress (Pa, tension positive).
double mean_stress(const double* sigma3);

/// The largest principal stress of a symmetric 3 x 3 stress (Pa, tension positive), by
/// the closed form for the eigenvalues of a symmetric 3 x 3 matrix.
double max_principal_stress(const double* sigma3);

/// The equivalent strain sqrt(2/3 e : e) of grad u (d x d; e the deviator of the 3 x 3 small
/// strain). In 2-D `eps_zz` is the out-of-plane strain: 0 in plane strain, -nu / (1 - nu)
/// (eps_xx + eps_yy) in elastic plane stress (without it a plane-stress bar read 9% low in
/// uniaxial tension, 26% low in a biaxial state).
double equivalent_strain(const double* H, int dim, double eps_zz = 0.0);

}  // namespace perinom

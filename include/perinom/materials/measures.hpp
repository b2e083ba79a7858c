#pragma once
/// @file Scalar measures of a stress or a displacement gradient, for output and probes.

namespace perinom {

/// Mean stress tr(sigma) / 3 of a 3 x 3 stress (Pa, tension positive).
double mean_stress(const double* sigma3);

/// The largest principal stress of a symmetric 3 x 3 stress (Pa, tension positive), by
/// the closed form for the eigenvalues of a symmetric 3 x 3 matrix.
double max_principal_stress(const double* sigma3);

/// The equivalent strain sqrt(2/3 e : e) of grad u (d x d; e the deviator of the 3 x 3 small
/// strain, plane strain in 2-D).
double equivalent_strain(const double* H, int dim);

}  // namespace perinom

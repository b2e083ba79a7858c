#pragma once
// The shape tensor of one family (internal to lib/operators), shared by bond_weights and the
// operator's refresh so that a refreshed row and a row built from scratch agree bit for bit.
#include <cstddef>
#include <cstdint>

#include "perinom/core/types.hpp"

namespace perinom {

/// K = sum_k wv[k] xi_k xi_k^T over the bonds k in [begin, end) with alive[k] (all when
/// alive is null), xi_k = x_{col[k]} - x_i, and K^-1 (both d x d, row-major). Returns false,
/// leaving Kinv zero, when K is singular: its smallest eigenvalue is at most 1e-10 of its
/// largest.
bool shape_tensor(int d, const double* x, std::size_t i, Offset begin, Offset end, const ParticleId* col,
                  const double* wv, const std::uint8_t* alive, double* K, double* Kinv);

/// q = det K / (tr K / d)^d: 1 for an isotropic family, 0 for one that does not span R^d.
double shape_quality(int d, const double* K);

}  // namespace perinom

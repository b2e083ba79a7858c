#pragma once
/// @file What a consistent-formulation model on a local part needs of the ranks (issue 19).
#include "perinom/neighbors/local_part.hpp"
#include "perinom/operators/consistent_gradient.hpp"

namespace perinom {

/// The CorrectionShare (consistent_gradient.hpp) of `part`: its owned and near counts, the ghost
/// exchange of a scalar field (a Halo of one value per particle over scratch the share keeps)
/// and the sums and maxima over the ranks. The part must outlive it.
CorrectionShare correction_share(const LocalPart& part);

}  // namespace perinom

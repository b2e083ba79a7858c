#pragma once
/// @file The variationally consistent gradient G~ (docs/theory.md, "consistent formulation";
/// the integration constraint of Chen, Hillman and Rueter 2013 on the nonlocal gradient).
#include <functional>
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/neighbors/families.hpp"
#include "perinom/operators/bond_weights.hpp"
#include "perinom/operators/nonlocal_operator.hpp"

namespace perinom {

/// How the correction went.
struct ConsistencyReport {
  int iterations = 0;            ///< preconditioned CG iterations (largest of the d solves)
  double residual = 0.0;         ///< |c - G~^T V 1| / |c - G^T V 1| after the solve
  double rhs_defect = 0.0;       ///< the part of the right-hand side outside L's range, relative
  double relative_change = 0.0;  ///< |G~ - G| / |G| over the stored weights
  bool converged = false;
};

/// A distributed rank's share of the correction (issue 19). The cloud is the rank's local part
/// (neighbors/local_part.hpp): its first `owned` particles are its own, the next `near` the
/// ghosts within one horizon, the rest the far ghosts. `exchange` fills the ghosts' entries of
/// a scalar field (one value per local particle) from their owners; `sum` adds `count` values
/// over the ranks, in place, and `max` takes their largest. The solve then runs over the owned unknowns of every rank, and the
/// owned and near rows get the corrected weights of the whole body (to the solve's tolerance);
/// the far rows keep their uncorrected ones (a local part never reads them).
struct CorrectionShare {
  std::size_t owned = 0, near = 0;
  std::function<void(double* field)> exchange;
  std::function<void(double* values, int count)> sum, max;
};

struct ConsistencyOptions {
  double tolerance = 1e-13;  ///< the CG's target, on the relative residual of the column constraints
  /// The correction counts as converged below this relative residual (rounding can keep the
  /// target out of reach on large clouds; the patch test's error is of this order).
  double converged_tolerance = 1e-11;
  int max_iterations = 50000;
  const CorrectionShare* ranks = nullptr;  ///< a distributed rank's share, or nullptr: the whole body
};

/// Corrects the gradient weights g of G (first- or second-order fit) to g~ = g + Delta such that
///  - G~ differentiates linear fields exactly, like G (sum_j Delta_ij xi_ij = 0);
///  - its columns satisfy the discrete divergence theorem sum_i V_i G~_b[i][j] = c_j[b], with
///    c the boundary measure (BoundaryTrace::column_measure);
///  - |Delta| is least in the norm sum_ij Delta_ij^2 / (w_ij V_j).
/// Then Delta_ij[b] = V_i w_ij V_j r_ij(gamma_b), with r_ij(f) = f_j - f_i - (G1 f)_i . xi_ij
/// the residual of the first-order least-squares fit (G1: the first-order operator of these
/// weights) of a scalar field gamma_b solving L gamma_b = c_b - G_b^T V 1. L is symmetric
/// positive semi-definite (gamma^T L gamma = sum_i V_i^2 sum_j w_ij V_j r_ij^2; null space: the
/// linear fields), solved by Jacobi-preconditioned CG, matrix-free (two bond passes per
/// iteration). Returns g~ as g~[k*d + b] for bond k (family order), for the operator of given
/// weights NonlocalOperator(G.shared_graph(), d, g~).
std::vector<double> consistent_gradient_weights(const PointCloud& cloud, const Families& families,
                                                const BondWeights& weights, const NonlocalOperator& G1,
                                                const NonlocalOperator& G,
                                                const std::vector<double>& c,
                                                const ConsistencyOptions& options = {},
                                                ConsistencyReport* report = nullptr);

}  // namespace perinom

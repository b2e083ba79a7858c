#pragma once
// Raw access to a NonlocalOperator's stored weights, for the code of this stage that builds
// on them in bulk (stabilizations, tangent rows, the consistent gradient). Internal to
// lib/operators: nothing outside this stage sees the operator's layout.
#include "perinom/operators/nonlocal_operator.hpp"

namespace perinom {

struct OperatorAccess {
  /// a_ij of bond k (M values, as stored).
  static double weight(const NonlocalOperator& D, Offset k, int r, Derivative which = Derivative::gradient) {
    return D.block(which).get(k, r);
  }
  static const double* weights(const NonlocalOperator& D, Offset k, double* scratch,
                               Derivative which = Derivative::gradient) {
    return D.block(which).stored(k, scratch);
  }
  /// a_mi of dual entry t (m = the entry's column), as stored.
  static double dual_weight(const NonlocalOperator& D, Offset t, int r, Derivative which = Derivative::gradient) {
    return D.block(which).get_dual(t, r);
  }
  /// -sum_j a_ij of row i (M values).
  static const double* diagonal(const NonlocalOperator& D, std::size_t i, Derivative which = Derivative::gradient) {
    const auto& b = D.block(which);
    return b.diag.data() + i * b.m;
  }
  /// w_ij V_j of bond k (zero for a dead bond is NOT applied here: check the graph).
  static const std::vector<double>& wv(const NonlocalOperator& D) { return D.wv_; }
  static const std::vector<double>& positions(const NonlocalOperator& D) { return D.x_; }
};

}  // namespace perinom

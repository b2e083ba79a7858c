#pragma once
/// @file Follower pressures for finite deformation: a pressure acts on the deformed surface.
/// The force it puts on a surface particle is f0 in the reference configuration
/// (Loading::pressure_force, -p N V / h) and cof(F) f0 on the deformed body (Nanson's
/// formula: n da = J F^-T N dA0, with cof(F) = J F^-T). The model carries the difference
/// (cof(F_i) - I) f0_i on its own side of the balance, so the solvers' external force stays
/// the reference one. Tractions given as vectors stay dead loads. The term has no stored
/// energy: the model's energy() leaves it out.
#include <cstddef>
#include <vector>

#include "perinom/models/loading.hpp"

namespace perinom {

/// cof(F) = J F^-T of a d x d F (d = 2: the in-plane block of plane strain, F_zz = 1).
void cofactor(const double* F, int d, double* cof);

class FollowerPressure {
 public:
  explicit FollowerPressure(int dim) : dim_(dim) {}
  /// Takes the pressures' reference forces of `loading` at factor s (O(N d), far below one
  /// force evaluation; not cached, so a loading changed in place is always seen).
  void follow(const Loading& loading, double s);
  bool active() const { return !particles_.empty(); }
  /// f_i -= (cof(I + H_i) - I) f0_i at the pressured particles (H: N x d x d, grad u).
  void add_force(const double* H, double* f) const;
  /// The derivative of that term: T_i[(a d + c) d + e] = -sum_b d cof_ab / dF_ce f0_ib at
  /// the pressured particles, zero elsewhere (T: N x d^3).
  void tangent(const double* H, std::vector<double>& T) const;

 private:
  int dim_;
  std::vector<double> f0_;               // N x d, the reference pressure force at s
  std::vector<std::size_t> particles_;   // the particles it acts on
};

}  // namespace perinom

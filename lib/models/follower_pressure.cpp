#include "perinom/models/follower_pressure.hpp"

#include <algorithm>

namespace perinom {
namespace {

// The permutation symbol in d = 2 (e_01 = 1) and d = 3 (e_012 = 1).
double levi_civita2(int a, int b) { return a == b ? 0.0 : (a == 0 ? 1.0 : -1.0); }
double levi_civita3(int a, int b, int c) { return 0.5 * (a - b) * (b - c) * (c - a); }

// d cof_aA / dF_bB at F (d x d): e_ab e_AB in 2-D (cof is linear in F), e_abc e_ABC F_cC in 3-D.
double cofactor_derivative(const double* F, int d, int a, int A, int b, int B) {
  if (d == 2) return levi_civita2(a, b) * levi_civita2(A, B);
  double s = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int C = 0; C < 3; ++C) s += levi_civita3(a, b, c) * levi_civita3(A, B, C) * F[c * 3 + C];
  return s;
}

}  // namespace

void cofactor(const double* F, int d, double* cof) {
  // cof_aA = e_ab e_AB F_bB (2-D), 1/2 e_abc e_ABC F_bB F_cC (3-D): each is
  // 1/(d-1) sum_bB (d cof_aA / dF_bB) F_bB.
  for (int a = 0; a < d; ++a)
    for (int A = 0; A < d; ++A) {
      double s = 0.0;
      for (int b = 0; b < d; ++b)
        for (int B = 0; B < d; ++B) s += cofactor_derivative(F, d, a, A, b, B) * F[b * d + B];
      cof[a * d + A] = s / (d - 1);
    }
}

void FollowerPressure::follow(const Loading& loading, double s) {
  particles_.clear();
  if (!loading.has_pressure()) return;
  const std::size_t dofs = std::max(loading.pressure_force.size(), loading.pressure_force0.size());
  f0_.resize(dofs);
  for (std::size_t k = 0; k < dofs; ++k) f0_[k] = loading.pressure_force_at(s, k);
  for (std::size_t i = 0; i < dofs / dim_; ++i)
    if (std::any_of(f0_.begin() + i * dim_, f0_.begin() + (i + 1) * dim_, [](double v) { return v != 0.0; }))
      particles_.push_back(i);
}

void FollowerPressure::add_force(const double* H, double* f) const {
  const int d = dim_, d2 = d * d;
  double F[9], cof[9];
  for (const std::size_t i : particles_) {
    for (int q = 0; q < d2; ++q) F[q] = H[i * d2 + q] + (q % (d + 1) == 0 ? 1.0 : 0.0);
    cofactor(F, d, cof);
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b) f[i * d + a] -= (cof[a * d + b] - (a == b ? 1.0 : 0.0)) * f0_[i * d + b];
  }
}

void FollowerPressure::tangent(const double* H, std::vector<double>& T) const {
  const int d = dim_, d2 = d * d, d3 = d2 * d;
  T.assign(f0_.size() / d * d3, 0.0);
  double F[9];
  for (const std::size_t i : particles_) {
    for (int q = 0; q < d2; ++q) F[q] = H[i * d2 + q] + (q % (d + 1) == 0 ? 1.0 : 0.0);
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c)
        for (int e = 0; e < d; ++e) {
          double s = 0.0;
          for (int b = 0; b < d; ++b) s -= cofactor_derivative(F, d, a, b, c, e) * f0_[i * d + b];
          T[i * d3 + (a * d + c) * d + e] = s;
        }
  }
}

}  // namespace perinom

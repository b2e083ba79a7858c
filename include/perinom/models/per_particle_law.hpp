#pragma once
/// @file The batch calls of PointwiseLaw for a law written particle by particle: Derived gives
/// stress(i, H_i, P_i) (keeping the trial state), tangent(i, H_i, C_i), cauchy(i, H_i, sigma_i)
/// and stored_energy(i) (of the kept trial state), and this base runs them over the particles
/// (the Drucker-Prager points and the finite-rotation wrapper share it).
#include <cstddef>
#include <vector>

#include "perinom/models/pointwise_law.hpp"

namespace perinom {

template <class Derived>
class PerParticleLaw : public PointwiseLaw {
 public:
  void stresses(std::size_t begin, std::size_t end, const double* H, double* P) override {
    const std::size_t d2 = dim2();
    for (std::size_t i = begin; i < end; ++i) self().stress(i, H + i * d2, P + i * d2);
  }
  void energies(std::size_t begin, std::size_t end, const double* H, double* psi) override {
    const std::size_t d2 = dim2();
    for (std::size_t i = begin; i < end; ++i) {
      double P[9];
      self().stress(i, H + i * d2, P);  // keeps the trial state whose stored energy this is
      psi[i] = self().stored_energy(i);
    }
  }
  std::size_t tangents(const double* H, std::vector<double>& C) const override {
    const std::size_t d2 = dim2(), d4 = d2 * d2, n = size();
    C.resize(n * d4);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) self().tangent(i, H + i * d2, C.data() + i * d4);
    return d4;
  }
  void cauchy(const double* H, double* sigma) const override {
    const std::size_t d2 = dim2(), n = size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) self().cauchy(i, H + i * d2, sigma + i * 9);
  }

 private:
  Derived& self() { return static_cast<Derived&>(*this); }
  const Derived& self() const { return static_cast<const Derived&>(*this); }
  std::size_t dim2() const { return static_cast<std::size_t>(dim()) * static_cast<std::size_t>(dim()); }
};

}  // namespace perinom

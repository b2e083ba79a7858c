// Follower pressures: cof(F) = J F^-T in 2-D and 3-D, the force term and its closed-form
// derivative against central differences, and the load factor's ramp between stages.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "perinom/models/follower_pressure.hpp"

using namespace perinom;

namespace {

// A deformation gradient's displacement part, far from the identity.
std::vector<double> gradient(int d, double shift) {
  std::vector<double> H(d * d);
  for (int q = 0; q < d * d; ++q) H[q] = 0.3 * std::sin(1.7 * q + shift);
  return H;
}

}  // namespace

TEST_CASE("the cofactor is J F^-T in 2-D and 3-D", "[models]") {
  for (const int d : {2, 3}) {
    const auto H = gradient(d, 0.4);
    Eigen::MatrixXd F(d, d);
    std::vector<double> Fv(d * d), cof(d * d);
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b) Fv[a * d + b] = F(a, b) = H[a * d + b] + (a == b ? 1.0 : 0.0);
    cofactor(Fv.data(), d, cof.data());
    const Eigen::MatrixXd expected = F.determinant() * F.inverse().transpose();
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b) CHECK(cof[a * d + b] == Approx(expected(a, b)).margin(1e-14));
  }
}

TEST_CASE("the follower term's tangent is its derivative, and it ramps like the loads", "[models]") {
  for (const int d : {2, 3}) {
    INFO("dimension " << d);
    // Three particles: the first and last pressed, the middle one free.
    Loading loading;
    loading.pressure_force.assign(3 * d, 0.0);
    loading.pressure_force0.assign(3 * d, 0.0);
    for (int a = 0; a < d; ++a) {
      loading.pressure_force[a] = -2.0 + a, loading.pressure_force[2 * d + a] = 0.5 * a + 1.0;
      loading.pressure_force0[a] = 1.0;
    }
    FollowerPressure follower(d);
    follower.follow(loading, 0.25);
    REQUIRE(follower.active());
    std::vector<double> H = gradient(d, 0.1), more = gradient(d, 2.0), H3;
    for (const auto& part : {H, more, gradient(d, 3.3)}) H3.insert(H3.end(), part.begin(), part.end());
    // The force at s = 0.25: -(cof(I + H_i) - I) f0_i with f0 = f0_stage + s (f - f0_stage).
    std::vector<double> f(3 * d, 0.0), cof(d * d), F(d * d);
    follower.add_force(H3.data(), f.data());
    for (int i : {0, 1, 2}) {
      for (int q = 0; q < d * d; ++q) F[q] = H3[i * d * d + q] + (q % (d + 1) == 0 ? 1.0 : 0.0);
      cofactor(F.data(), d, cof.data());
      for (int a = 0; a < d; ++a) {
        double expected = 0.0;
        for (int b = 0; b < d; ++b) {
          const double f0 = loading.pressure_force0[i * d + b] +
                            0.25 * (loading.pressure_force[i * d + b] - loading.pressure_force0[i * d + b]);
          expected -= (cof[a * d + b] - (a == b ? 1.0 : 0.0)) * f0;
        }
        CHECK(f[i * d + a] == Approx(expected).margin(1e-14));
      }
    }
    // T against central differences in every component of H.
    std::vector<double> T;
    follower.tangent(H3.data(), T);
    const int d3 = d * d * d;
    const double h = 1e-6;
    double err = 0.0, ref = 0.0;
    for (int i : {0, 1, 2})
      for (int c = 0; c < d; ++c)
        for (int e = 0; e < d; ++e) {
          std::vector<double> Hp = H3, Hm = H3, fp(3 * d, 0.0), fm(3 * d, 0.0);
          Hp[i * d * d + c * d + e] += h, Hm[i * d * d + c * d + e] -= h;
          follower.add_force(Hp.data(), fp.data());
          follower.add_force(Hm.data(), fm.data());
          for (int a = 0; a < d; ++a) {
            const double fd = (fp[i * d + a] - fm[i * d + a]) / (2 * h);
            err = std::max(err, std::abs(fd - T[i * d3 + (a * d + c) * d + e]));
            ref = std::max(ref, std::abs(fd));
          }
        }
    INFO("max |T - FD| " << err << " of " << ref);
    CHECK(err < 1e-8 * ref);
    CHECK(ref > 0.1);
  }
}

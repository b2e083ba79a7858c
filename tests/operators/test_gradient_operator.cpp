#include <catch2/catch.hpp>

#include "../support/clouds.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/operators/nonlocal_operator.hpp"

using namespace perinom;

namespace {

NonlocalOperator make_G(const PointCloud& c, const Families& f, Influence w) {
  return NonlocalOperator(c, f, bond_weights(c, f, w));
}

}  // namespace

TEST_CASE("the gradient is exact for linear fields on jittered clouds, boundaries included",
          "[operators]") {
  for (int dim : {2, 3}) {
    const PointCloud c = test::lattice(dim, dim == 2 ? 14 : 7, 0.4);
    for (bool knn : {false, true}) {
      const Families f = knn ? knn_families(c, dim == 2 ? 14 : 33) : radius_families(c, 3.015);
      for (Influence w : {Influence::constant, Influence::inverse_square, Influence::gaussian}) {
        const NonlocalOperator G = make_G(c, f, w);
        // u_a(x) = B_ab x_b + c_a with a full, non-symmetric B.
        const std::vector<double> B = test::random_field(dim * dim, 1.0, 5);
        std::vector<double> u(c.size() * dim), H(c.size() * dim * dim);
        for (std::size_t i = 0; i < c.size(); ++i)
          for (int a = 0; a < dim; ++a) {
            u[i * dim + a] = 0.3 * (a + 1);
            for (int b = 0; b < dim; ++b) u[i * dim + a] += B[a * dim + b] * c.x[i * dim + b];
          }
        G.apply(u.data(), dim, H.data());
        double err = 0.0;
        for (std::size_t i = 0; i < c.size(); ++i)
          for (int k = 0; k < dim * dim; ++k) err = std::max(err, std::abs(H[i * dim * dim + k] - B[k]));
        INFO("dim " << dim << (knn ? " knn" : " radius") << " weight " << int(w));
        CHECK(err / test::max_abs(B) <= 1e-12);
      }
    }
  }
}

TEST_CASE("the transposed product is the adjoint of the gradient product", "[operators]") {
  for (int dim : {2, 3}) {
    const PointCloud c = test::lattice(dim, dim == 2 ? 12 : 6, 0.3);
    for (bool knn : {false, true}) {
      const Families f = knn ? knn_families(c, dim == 2 ? 9 : 20) : radius_families(c, 2.015);
      const NonlocalOperator G = make_G(c, f, Influence::inverse_square);
      for (int nc : {1, dim}) {
        const auto u = test::random_field(c.size() * nc, 1.0, 1);
        const auto q = test::random_field(c.size() * nc * dim, 1.0, 2);
        std::vector<double> Gu(q.size()), Gtq(u.size());
        G.apply(u.data(), nc, Gu.data());
        G.apply_transpose(q.data(), nc, Gtq.data());
        double lhs = 0.0, rhs = 0.0, scale = 0.0;
        for (std::size_t k = 0; k < q.size(); ++k) lhs += Gu[k] * q[k], scale += std::abs(Gu[k] * q[k]);
        for (std::size_t k = 0; k < u.size(); ++k) rhs += u[k] * Gtq[k];
        CHECK(std::abs(lhs - rhs) <= 1e-13 * scale);
      }
    }
  }
}

TEST_CASE("the transposed product equals the explicit dual-support sum for k-nearest families",
          "[operators]") {
  const PointCloud c = test::lattice(2, 12, 0.45);
  const Families f = knn_families(c, 11);
  const BondWeights bw = bond_weights(c, f, Influence::inverse_distance);
  const NonlocalOperator G(c, f, bw);
  const int d = 2;
  const auto q = test::random_field(c.size() * d, 1.0, 9);  // nc = 1
  std::vector<double> out(c.size());
  G.apply_transpose(q.data(), 1, out.data());
  // (G^T q)_i = sum_b [ -sum_j g_ij[b] q_i[b] + sum_{m : i in H_m} g_mi[b] q_m[b] ],
  // g_mi = w_mi V_i K_m^-1 xi_mi, computed here bond by bond from the families alone.
  std::vector<double> ref(c.size(), 0.0);
  for (std::size_t m = 0; m < c.size(); ++m)
    for (Offset k = f.begin(m); k < f.end(m); ++k) {
      const std::size_t i = f.neighbors[k];
      const double* Kinv = bw.shape_inverse.data() + m * d * d;
      for (int b = 0; b < d; ++b) {
        double g = 0.0;
        for (int e = 0; e < d; ++e) g += Kinv[b * d + e] * (c.x[i * d + e] - c.x[m * d + e]);
        g *= bw.wv[k];
        ref[i] += g * q[m * d + b];
        ref[m] -= g * q[m * d + b];
      }
    }
  for (std::size_t i = 0; i < c.size(); ++i) CHECK(out[i] == Approx(ref[i]).margin(1e-12 * test::max_abs(ref)));
}

TEST_CASE("a family that does not span R^d is reported with its particle", "[operators]") {
  const PointCloud c = test::lattice(2, 6, 0.0);
  const Families f = radius_families(c, 0.9);  // no neighbour at all
  CHECK_THROWS_WITH(bond_weights(c, f, Influence::constant),
                    Catch::Contains("particle 0") && Catch::Contains("singular"));
}

TEST_CASE("single-precision weights: constants exact, linear fields to float rounding",
          "[operators]") {
  for (int dim : {2, 3}) {
    const PointCloud c = test::lattice(dim, dim == 2 ? 14 : 7, 0.4);
    const Families f = radius_families(c, 3.015);
    const BondWeights bw = bond_weights(c, f, Influence::inverse_square);
    const NonlocalOperator G64(c, f, bw), G32(c, f, bw, OperatorOptions{1, false, WeightPrecision::float32});
    REQUIRE(G32.precision() == WeightPrecision::float32);
    CHECK(G32.memory_bytes() < G64.memory_bytes());
    const std::vector<double> B = test::random_field(dim * dim, 1.0, 5);
    std::vector<double> u(c.size() * dim), one(c.size() * dim, 0.7), H(c.size() * dim * dim);
    for (std::size_t i = 0; i < c.size(); ++i)
      for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) u[i * dim + a] += B[a * dim + b] * c.x[i * dim + b];
    // Constants: the diagonal is summed from the rounded weights, so G 1 = 0 to double rounding.
    G32.apply(one.data(), dim, H.data());
    CHECK(test::max_abs(H) <= 1e-12);
    G32.apply(u.data(), dim, H.data());
    double err = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i)
      for (int k = 0; k < dim * dim; ++k) err = std::max(err, std::abs(H[i * dim * dim + k] - B[k]));
    WARN("dim " << dim << ": float32 weights, gradient of a linear field off by " << err / test::max_abs(B));
    CHECK(err / test::max_abs(B) <= 1e-5);
    CHECK(err / test::max_abs(B) >= 1e-10);  // really rounded: the option is not a no-op
    // Both products agree with the double-precision operator to float rounding.
    const auto q = test::random_field(c.size() * dim * dim, 1.0, 3);
    std::vector<double> f64(c.size() * dim), f32(c.size() * dim);
    G64.apply_transpose(q.data(), dim, f64.data());
    G32.apply_transpose(q.data(), dim, f32.data());
    double diff = 0.0;
    for (std::size_t k = 0; k < f64.size(); ++k) diff = std::max(diff, std::abs(f64[k] - f32[k]));
    CHECK(diff <= 1e-5 * test::max_abs(f64));
  }
}

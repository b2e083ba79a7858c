#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <memory>

#include "../support/clouds.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/operators/stabilization.hpp"

using namespace perinom;

namespace {

struct Setup {
  PointCloud cloud;
  Families families;
  BondWeights weights;
  NonlocalOperator G;
  std::vector<double> c;
  std::unique_ptr<Stabilization> op;  // refers to G: built in place, never moved
  ScalarCsr S;
};

// S of the fit of `order` (2: with its Hessian), scaled as the correspondence force scales it.
void make(Setup& s, int dim, int n, bool knn, int order = 1) {
  s.cloud = test::lattice(dim, n, 0.35);
  s.families = knn ? knn_families(s.cloud, dim == 2 ? 12 : 30) : radius_families(s.cloud, order == 2 ? 3.015 : 2.015);
  s.weights = bond_weights(s.cloud, s.families, Influence::inverse_square);
  s.G = NonlocalOperator(s.cloud, s.families, s.weights, OperatorOptions{order, order == 2});
  s.c = stabilization_coefficients(s.G, 0.5, 1.0);
  s.op = std::make_unique<Stabilization>(s.cloud, s.G, 0.5 * 2.0 * 1.0);
  REQUIRE(s.op->order() == order);
  s.S = assemble_stabilization(*s.op, s.cloud.size());
}

/// The fit's basis at xi: xi, then (order 2) xi_a xi_b with 1/2 on the diagonal.
std::vector<double> basis(const double* xi, int d, int order) {
  std::vector<double> p(xi, xi + d);
  if (order == 2)
    for (int a = 0; a < d; ++a)
      for (int b = a; b < d; ++b) p.push_back(a == b ? 0.5 * xi[a] * xi[a] : xi[a] * xi[b]);
  return p;
}

/// W_s = 1/2 sum_i V_i c_i sum_j w_ij V_j z_ij^2 for a scalar field, z_ij = u_j - u_i - D_i p_ij
/// (THEORY sec. 4 and 6), straight from the definition.
double stabilization_energy(const Setup& s, const std::vector<double>& u, const std::vector<double>& factor = {}) {
  const int d = s.cloud.dim, order = s.op->order(), m = d * (d + 1) / 2;
  std::vector<double> D(s.cloud.size() * d), Hs(s.cloud.size() * m);
  s.G.apply(u.data(), 1, D.data());
  if (order == 2) s.G.apply(u.data(), 1, Hs.data(), Derivative::hessian);
  double W = 0.0;
  for (std::size_t i = 0; i < s.cloud.size(); ++i)
    for (Offset k = s.families.begin(i); k < s.families.end(i); ++k) {
      const std::size_t j = s.families.neighbors[k];
      double xi[3];
      for (int b = 0; b < d; ++b) xi[b] = s.cloud.x[j * d + b] - s.cloud.x[i * d + b];
      const std::vector<double> p = basis(xi, d, order);
      double z = u[j] - u[i];
      for (int b = 0; b < d; ++b) z -= D[i * d + b] * p[b];
      if (order == 2)
        for (int q = 0; q < m; ++q) z -= Hs[i * m + q] * p[d + q];
      W += 0.5 * s.cloud.volume[i] * s.c[i] * (factor.empty() ? 1.0 : factor[i]) * s.weights.wv[k] * z * z;
    }
  return W;
}

Eigen::MatrixXd dense(const ScalarCsr& S) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(S.rows(), S.rows());
  for (std::size_t i = 0; i < S.rows(); ++i)
    for (Offset k = S.offsets[i]; k < S.offsets[i + 1]; ++k) A(i, S.cols[k]) = S.values[k];
  return A;
}

}  // namespace

TEST_CASE("S is zero on fields of the fit's order: linear for order 1 and quadratic for order 2", "[operators][stabilization]") {
  for (int order : {1, 2})
  for (int dim : {2, 3})
    for (bool knn : {false, true}) {
      Setup s;
      make(s, dim, dim == 2 ? 10 : 5, knn, order);
      std::vector<double> u(s.cloud.size()), Su(s.cloud.size(), 0.0);
      for (std::size_t i = 0; i < u.size(); ++i) {
        const double x = s.cloud.x[i * dim], y = s.cloud.x[i * dim + dim - 1];
        u[i] = 0.7 - 1.3 * x + 0.4 * y + (order == 2 ? 2.1 * x * x - 0.8 * x * y + 1.7 * y * y : 0.0);
      }
      s.S.apply_add(u.data(), 1, Su.data());
      double scale = 0.0;
      for (double v : s.S.values) scale = std::max(scale, std::abs(v));
      INFO("order " << order << ", dim " << dim << (knn ? " knn" : " radius"));
      CHECK(test::max_abs(Su) <= 1e-12 * scale * test::max_abs(u) * 10);
      CHECK(scale > 0.0);
    }
}

TEST_CASE("S is symmetric positive semi-definite with the fields of the fit's order as its null space", "[operators][stabilization]") {
  for (int order : {1, 2})
  for (int dim : {2, 3})
    for (bool knn : {false, true}) {
      Setup s;
      make(s, dim, dim == 2 ? 9 : 4, knn, order);
      INFO("order " << order << ", dim " << dim << (knn ? " knn" : " radius"));
      const Eigen::MatrixXd A = dense(s.S);
      const double scale = A.cwiseAbs().maxCoeff();
      CHECK((A - A.transpose()).cwiseAbs().maxCoeff() <= 1e-13 * scale);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (A + A.transpose()));
      INFO("smallest eigenvalue " << eig.eigenvalues().minCoeff() << ", largest " << eig.eigenvalues().maxCoeff());
      CHECK(eig.eigenvalues().minCoeff() >= -1e-12 * eig.eigenvalues().maxCoeff());
      // The null space holds the fields of the fit's order (1 + the basis size) and should hold
      // no more on a well-connected cloud: the stabilization acts on every other mode.
      int zero = 0;
      for (int k = 0; k < A.rows(); ++k) zero += eig.eigenvalues()[k] < 1e-10 * eig.eigenvalues().maxCoeff();
      CHECK(zero == 1 + s.op->basis_size());
    }
}

TEST_CASE("S u is the derivative of the bond-by-bond stabilization energy", "[operators][stabilization]") {
  for (int order : {1, 2})
  for (int dim : {2, 3})
    for (bool knn : {false, true}) {
      Setup s;
      make(s, dim, dim == 2 ? 8 : 4, knn, order);
      INFO("order " << order << ", dim " << dim << (knn ? " knn" : " radius"));
      const auto u = test::random_field(s.cloud.size(), 1e-3, 4);
      std::vector<double> Su(u.size(), 0.0);
      s.S.apply_add(u.data(), 1, Su.data());
      // W_s is quadratic, so u.S u = 2 W_s exactly and central differences are exact too.
      double uSu = 0.0;
      for (std::size_t k = 0; k < u.size(); ++k) uSu += u[k] * Su[k];
      CHECK(uSu == Approx(2.0 * stabilization_energy(s, u)).epsilon(1e-11));
      for (std::size_t k = 0; k < u.size(); k += 7) {
        auto up = u, um = u;
        const double h = 1e-4;
        up[k] += h, um[k] -= h;
        const double fd = (stabilization_energy(s, up) - stabilization_energy(s, um)) / (2 * h);
        CHECK(Su[k] == Approx(fd).epsilon(1e-7).margin(1e-9 * test::max_abs(Su)));
      }
    }
}

TEST_CASE("the matrix-free stabilization equals the assembled S on vector fields", "[operators][stabilization]") {
  for (int dim : {2, 3})
    for (bool knn : {false, true}) {
      Setup s;
      make(s, dim, dim == 2 ? 10 : 5, knn);
      const std::size_t n = s.cloud.size();
      const auto u = test::random_field(n * dim, 1e-3, 6);
      std::vector<double> H(n * dim * dim), B(n * dim * dim), r(n * dim), free(n * dim), assembled(n * dim, 0.0);
      s.G.apply(u.data(), dim, H.data());
      s.op->bond_terms(u.data(), H.data(), B.data(), r.data());
      s.G.apply_transpose(B.data(), dim, free.data());
      for (auto& v : free) v = -v;
      s.op->add_direct(u.data(), H.data(), r.data(), free.data());
      s.S.apply_add(u.data(), dim, assembled.data());
      double err = 0.0;
      for (std::size_t k = 0; k < free.size(); ++k) err = std::max(err, std::abs(free[k] - assembled[k]));
      INFO("dim " << dim << (knn ? " knn" : " radius"));
      CHECK(err <= 1e-11 * test::max_abs(assembled));
    }
}

TEST_CASE("the second-order bond passes equal the assembled S on d components and on one and W_s is u.Su/2",
          "[operators][stabilization]") {
  for (int dim : {2, 3})
    for (bool knn : {false, true}) {
      Setup s;
      make(s, dim, dim == 2 ? 10 : 5, knn, 2);
      const std::size_t n = s.cloud.size();
      const int m = s.G.hessian_terms();
      INFO("dim " << dim << (knn ? " knn" : " radius"));
      for (const int components : {dim, 1}) {
        const auto u = test::random_field(n * components, 1e-3, 6);
        std::vector<double> grad(n * components * dim), hess(n * components * m);
        std::vector<double> free(n * components, 0.0), assembled(n * components, 0.0);
        s.G.apply(u.data(), components, grad.data());
        s.G.apply(u.data(), components, hess.data(), Derivative::hessian);
        s.op->add_force(u.data(), components, grad.data(), hess.data(), free.data());
        s.S.apply_add(u.data(), components, assembled.data());
        double err = 0.0, uSu = 0.0;
        for (std::size_t k = 0; k < free.size(); ++k) {
          err = std::max(err, std::abs(free[k] - assembled[k]));
          uSu += u[k] * assembled[k];
        }
        CHECK(err <= 1e-11 * test::max_abs(assembled));
        CHECK(s.op->energy(u.data(), components, grad.data(), hess.data()) == Approx(0.5 * uSu).epsilon(1e-11));
      }
      // B belongs to the first-order form only.
      std::vector<double> B(n * dim * dim), r(n * dim), u(n * dim, 0.0), g(n * dim * dim), h(n * dim * m);
      CHECK_THROWS_AS(s.op->bond_terms(u.data(), dim, g.data(), h.data(), B.data(), r.data()), std::invalid_argument);
    }
}

TEST_CASE("centre factors scale each family's block: force, rows and energy follow c_i factor_i", "[operators][stabilization]") {
  // The secant stabilization of a plastic body (model.stabilization_scale: secant) scales
  // each centre's block by its particle's factor; the force (bond passes), the rows (Newton's
  // tangent, assembled here) and the energy must all be the sum of the scaled blocks.
  for (int order : {1, 2})
    for (int dim : {2, 3}) {
      Setup s;
      make(s, dim, dim == 2 ? 8 : 4, false, order);
      const std::size_t n = s.cloud.size();
      INFO("order " << order << ", dim " << dim);
      s.op->set_centre_factors(std::vector<double>(n, 1.0));
      const ScalarCsr same = assemble_stabilization(*s.op, n);
      CHECK(same.values == s.S.values);  // factors of 1 change nothing, to the bit
      const auto factor = test::random_field(n, 1.0, 9);  // in (-1, 1): take |.|, some near 0
      std::vector<double> f(n);
      for (std::size_t i = 0; i < n; ++i) f[i] = std::abs(factor[i]);
      s.op->set_centre_factors(f);
      const ScalarCsr S = assemble_stabilization(*s.op, n);
      const auto u = test::random_field(n, 1e-3, 4);
      std::vector<double> Su(n, 0.0);
      S.apply_add(u.data(), 1, Su.data());
      double uSu = 0.0;
      for (std::size_t k = 0; k < n; ++k) uSu += u[k] * Su[k];
      CHECK(uSu == Approx(2.0 * stabilization_energy(s, u, f)).epsilon(1e-11));
      CHECK(uSu < 0.9 * 2.0 * stabilization_energy(s, u));  // and it did change
      for (std::size_t k = 0; k < n; k += 7) {
        auto up = u, um = u;
        const double h = 1e-4;
        up[k] += h, um[k] -= h;
        const double fd = (stabilization_energy(s, up, f) - stabilization_energy(s, um, f)) / (2 * h);
        CHECK(Su[k] == Approx(fd).epsilon(1e-7).margin(1e-9 * test::max_abs(Su)));
      }
      if (order == 2) {
        // The bond passes (the explicit force) against the rows.
        std::vector<double> grad(n * dim), hess(n * s.G.hessian_terms()), free(n, 0.0);
        s.G.apply(u.data(), 1, grad.data());
        s.G.apply(u.data(), 1, hess.data(), Derivative::hessian);
        s.op->add_force(u.data(), 1, grad.data(), hess.data(), free.data());
        double err = 0.0;
        for (std::size_t k = 0; k < n; ++k) err = std::max(err, std::abs(free[k] - Su[k]));
        CHECK(err <= 1e-11 * test::max_abs(Su));
      }
      CHECK_THROWS_AS(s.op->set_centre_factors(std::vector<double>(n + 1, 1.0)), std::invalid_argument);
    }
}

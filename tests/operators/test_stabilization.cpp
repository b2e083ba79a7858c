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

void make(Setup& s, int dim, int n, bool knn) {
  s.cloud = test::lattice(dim, n, 0.35);
  s.families = knn ? knn_families(s.cloud, dim == 2 ? 12 : 30) : radius_families(s.cloud, 2.015);
  s.weights = bond_weights(s.cloud, s.families, Influence::inverse_square);
  s.G = NonlocalOperator(s.cloud, s.families, s.weights);
  s.c = stabilization_coefficients(s.G, 0.5, 1.0);
  s.op = std::make_unique<Stabilization>(s.cloud, s.G, 0.5 * 2.0 * 1.0);
  s.S = assemble_stabilization(*s.op, s.cloud.size());
}

/// W_s = 1/2 sum_i V_i c_i sum_j w_ij V_j |z_ij|^2 for a scalar field, straight from THEORY sec. 4.
double stabilization_energy(const Setup& s, const std::vector<double>& u) {
  const int d = s.cloud.dim;
  std::vector<double> grad(s.cloud.size() * d);
  s.G.apply(u.data(), 1, grad.data());
  double W = 0.0;
  for (std::size_t i = 0; i < s.cloud.size(); ++i)
    for (Offset k = s.families.begin(i); k < s.families.end(i); ++k) {
      const std::size_t j = s.families.neighbors[k];
      double z = u[j] - u[i];
      for (int b = 0; b < d; ++b) z -= grad[i * d + b] * (s.cloud.x[j * d + b] - s.cloud.x[i * d + b]);
      W += 0.5 * s.cloud.volume[i] * s.c[i] * s.weights.wv[k] * z * z;
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

TEST_CASE("S is zero on linear fields", "[operators][stabilization]") {
  for (int dim : {2, 3})
    for (bool knn : {false, true}) {
      Setup s;
      make(s, dim, dim == 2 ? 10 : 5, knn);
      std::vector<double> u(s.cloud.size()), Su(s.cloud.size(), 0.0), ones(s.cloud.size(), 1.0), Sone(s.cloud.size(), 0.0);
      for (std::size_t i = 0; i < u.size(); ++i) u[i] = 0.7 - 1.3 * s.cloud.x[i * dim] + 0.4 * s.cloud.x[i * dim + dim - 1];
      s.S.apply_add(u.data(), 1, Su.data());
      double scale = 0.0;
      for (double v : s.S.values) scale = std::max(scale, std::abs(v));
      CHECK(test::max_abs(Su) <= 1e-12 * scale * test::max_abs(u) * 10);
    }
}

TEST_CASE("S is symmetric positive semi-definite", "[operators][stabilization]") {
  for (int dim : {2, 3})
    for (bool knn : {false, true}) {
      Setup s;
      make(s, dim, dim == 2 ? 9 : 4, knn);
      const Eigen::MatrixXd A = dense(s.S);
      const double scale = A.cwiseAbs().maxCoeff();
      CHECK((A - A.transpose()).cwiseAbs().maxCoeff() <= 1e-13 * scale);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (A + A.transpose()));
      INFO("smallest eigenvalue " << eig.eigenvalues().minCoeff() << ", largest " << eig.eigenvalues().maxCoeff());
      CHECK(eig.eigenvalues().minCoeff() >= -1e-12 * eig.eigenvalues().maxCoeff());
      // The null space holds the linear fields (d + 1 of them) and should hold no more on a
      // well-connected cloud: the stabilization acts on every other mode.
      int zero = 0;
      for (int k = 0; k < A.rows(); ++k) zero += eig.eigenvalues()[k] < 1e-10 * eig.eigenvalues().maxCoeff();
      CHECK(zero == dim + 1);
    }
}

TEST_CASE("S u is the derivative of the bond-by-bond stabilization energy", "[operators][stabilization]") {
  for (int dim : {2, 3})
    for (bool knn : {false, true}) {
      Setup s;
      make(s, dim, dim == 2 ? 8 : 4, knn);
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

// Accuracy of the second-order nonlocal gradient and Hessian (seed 002 sec. 6.1, THEORY sec. 6).
//
// The field w(x, y) = exp(xy) (sin 3(x - y) - cos 2(x + y)) on [-1, 1]^2 is sampled on a
// regular cell-centred lattice of n x n particles (spacing h = 2/n), families are the k nearest
// neighbours, influence w(r) = 1/r^2 (the seed's default). The relative L2 error of the Hessian
// (seed 002 eq. 102; volumes are equal, so they cancel) is
//   e_H = sqrt( sum_i |Hess w_i - H_i|_F^2 / sum_i |Hess w_i|_F^2 ),
// with H_i the nonlocal Hessian (all four entries of the symmetric 2 x 2 matrix), and e_g the
// same for the gradient. Both are reported over all particles, over the interior (particles
// whose family's disc of radius delta_i lies inside the square, so the fit is not one-sided)
// and over the boundary band (the rest). For comparison, the first-order gradient
// (NonlocalOperator of order 1, THEORY sec. 2) of the same families and weights is measured too.
//
// Run (verification/hessian_accuracy/hessian_accuracy.py does, and plots):
//   hessian_accuracy sweep 20,40,60 14          one CSV row per (n, k), on stdout
//   hessian_accuracy sweep 60 6,8,10,14,20 inverse_square
//   hessian_accuracy layers 100 14               errors by layer counted from the boundary
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "perinom/core/error.hpp"
#include "perinom/geometry/lattice.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/operators/nonlocal_operator.hpp"

using namespace perinom;

namespace {

/// w and its exact derivatives at (x, y): value, (w_x, w_y), (w_xx, w_xy, w_yy).
struct Exact {
  double w, g[2], h[3];
};

Exact field(double x, double y) {
  const double E = std::exp(x * y), Ex = y * E, Ey = x * E;
  const double Exx = y * y * E, Exy = (1.0 + x * y) * E, Eyy = x * x * E;
  const double s = std::sin(3.0 * (x - y)), c = std::cos(3.0 * (x - y));
  const double S = std::sin(2.0 * (x + y)), C = std::cos(2.0 * (x + y));
  const double f = s - C, fx = 3.0 * c + 2.0 * S, fy = -3.0 * c + 2.0 * S;
  const double fxx = -9.0 * s + 4.0 * C, fxy = 9.0 * s + 4.0 * C, fyy = fxx;
  return {E * f,
          {Ex * f + E * fx, Ey * f + E * fy},
          {Exx * f + 2.0 * Ex * fx + E * fxx, Exy * f + Ex * fy + Ey * fx + E * fxy,
           Eyy * f + 2.0 * Ey * fy + E * fyy}};
}

/// Sums of squared errors and of squared exact values, for one set of particles.
struct L2 {
  double err = 0.0, ref = 0.0;
  double relative() const { return ref > 0.0 ? std::sqrt(err / ref) : 0.0; }
};

/// One particle's contributions: the gradient's 2 entries; the Hessian's 4 (xy twice).
void add_gradient(const Exact& e, const double* g, L2& eg) {
  for (int b = 0; b < 2; ++b) eg.err += std::pow(g[b] - e.g[b], 2), eg.ref += e.g[b] * e.g[b];
}
void add_hessian(const Exact& e, const double* h, L2& eh) {
  for (int s = 0; s < 3; ++s) {
    const double count = s == 1 ? 2.0 : 1.0;
    eh.err += count * std::pow(h[s] - e.h[s], 2);
    eh.ref += count * e.h[s] * e.h[s];
  }
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The best of a few runs of a product (seconds).
template <class F>
double best_of(int runs, F&& f) {
  double best = 1e300;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, seconds_since(t0));
  }
  return best;
}

std::vector<int> parse_list(const std::string& s) {
  std::vector<int> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::stoi(item));
  return v;
}

/// Everything one (n, k) case produces.
struct Case {
  PointCloud cloud;
  Families families;
  NonlocalOperator D;
  std::vector<double> w, grad, hess, grad1;  // grad1: the first-order gradient
  double t_search = 0, t_assembly = 0, t_gradient = 0, t_hessian = 0;
};

// Steps 1-4 for one resolution and neighbour count.
Case run_case(int n, int k, Influence influence) {
  Case c;
  // 1. The lattice: n x n cells on [-1, 1]^2, one particle at each centre.
  BoxGeometry box;
  box.dim = 2;
  box.min = {-1.0, -1.0, 0.0};
  box.max = {1.0, 1.0, 0.0};
  c.cloud = make_lattice(box, 2.0 / n);
  // 2. The k nearest neighbours, the bond weights w_ij V_j and the second-order operators.
  auto t0 = std::chrono::steady_clock::now();
  c.families = knn_families(c.cloud, k);
  c.t_search = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const BondWeights bw = bond_weights(c.cloud, c.families, influence);
  c.D = NonlocalOperator(c.cloud, c.families, bw, OperatorOptions{2, true});
  c.t_assembly = seconds_since(t0);
  const NonlocalOperator G(c.cloud, c.families, bw);  // the first-order gradient, to compare
  // 3. The field at the particles, and its nonlocal gradient and Hessian.
  const std::size_t N = c.cloud.size();
  c.w.resize(N);
  for (std::size_t i = 0; i < N; ++i) c.w[i] = field(c.cloud.x[2 * i], c.cloud.x[2 * i + 1]).w;
  c.grad.resize(2 * N);
  c.hess.resize(3 * N);
  c.grad1.resize(2 * N);
  G.apply(c.w.data(), 1, c.grad1.data());
  c.t_gradient = best_of(20, [&] { c.D.apply(c.w.data(), 1, c.grad.data()); });
  c.t_hessian = best_of(20, [&] { c.D.apply(c.w.data(), 1, c.hess.data(), Derivative::hessian); });
  return c;
}

/// Distance from particle i to the boundary of the square.
double to_boundary(const PointCloud& cloud, std::size_t i) {
  const double x = cloud.x[2 * i], y = cloud.x[2 * i + 1];
  return std::min({1.0 - std::abs(x), 1.0 - std::abs(y)});
}

int sweep(const std::vector<int>& ns, const std::vector<int>& ks, Influence influence) {
  std::printf("n,N,k,h,status,grad_err,hess_err,grad_err_interior,hess_err_interior,"
              "grad_err_boundary,hess_err_boundary,grad1_err,grad1_err_interior,grad1_err_boundary,"
              "interior_fraction,t_search,t_assembly,t_gradient,t_hessian,operator_bytes\n");
  for (const int n : ns)
    for (const int k : ks) {
      const double h = 2.0 / n;
      Case c;
      try {
        c = run_case(n, k, influence);
      } catch (const InputError& e) {
        // A family that cannot hold a quadratic: reported, not measured.
        std::printf("%d,%d,%d,%.10g,singular,,,,,,,,,,,,,,,\n", n, n * n, k, h);
        std::cerr << "n = " << n << ", k = " << k << ": " << e.what() << "\n";
        continue;
      }
      // 4. The errors over all particles, the interior and the boundary band.
      L2 g_all, h_all, g_in, h_in, g_bd, h_bd, g1_all, g1_in, g1_bd;
      std::size_t interior = 0;
      for (std::size_t i = 0; i < c.cloud.size(); ++i) {
        const Exact e = field(c.cloud.x[2 * i], c.cloud.x[2 * i + 1]);
        const bool inside = to_boundary(c.cloud, i) >= c.families.support[i];
        interior += inside;
        for (L2* l2 : {&g_all, inside ? &g_in : &g_bd}) add_gradient(e, &c.grad[2 * i], *l2);
        for (L2* l2 : {&h_all, inside ? &h_in : &h_bd}) add_hessian(e, &c.hess[3 * i], *l2);
        for (L2* l2 : {&g1_all, inside ? &g1_in : &g1_bd}) add_gradient(e, &c.grad1[2 * i], *l2);
      }
      std::printf("%d,%d,%d,%.10g,ok,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6f,%.6e,%.6e,"
                  "%.6e,%.6e,%zu\n",
                  n, n * n, k, h, g_all.relative(), h_all.relative(), g_in.relative(),
                  h_in.relative(), g_bd.relative(), h_bd.relative(), g1_all.relative(),
                  g1_in.relative(), g1_bd.relative(),
                  double(interior) / c.cloud.size(), c.t_search, c.t_assembly, c.t_gradient,
                  c.t_hessian, c.D.memory_bytes());
      std::fflush(stdout);
    }
  return 0;
}

// The errors by layer: layer l holds the particles whose distance to the boundary lies in
// [l h, (l + 1) h), so layer 0 is the outermost row of particles. Sums of squares per layer
// (errors and exact values), so the script can normalise as it likes.
int layers(int n, int k, Influence influence) {
  const Case c = run_case(n, k, influence);
  const double h = 2.0 / n;
  std::vector<L2> g(n), hs(n);
  std::vector<std::size_t> count(n, 0);
  for (std::size_t i = 0; i < c.cloud.size(); ++i) {
    const int l = static_cast<int>(to_boundary(c.cloud, i) / h);
    const Exact e = field(c.cloud.x[2 * i], c.cloud.x[2 * i + 1]);
    add_gradient(e, &c.grad[2 * i], g[l]);
    add_hessian(e, &c.hess[3 * i], hs[l]);
    ++count[l];
  }
  std::printf("layer,particles,grad_sq_err,grad_sq_exact,hess_sq_err,hess_sq_exact\n");
  for (int l = 0; l < n; ++l)
    if (count[l])
      std::printf("%d,%zu,%.6e,%.6e,%.6e,%.6e\n", l, count[l], g[l].err, g[l].ref, hs[l].err,
                  hs[l].ref);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string usage =
      "usage: hessian_accuracy sweep N_LIST K_LIST [influence]\n"
      "       hessian_accuracy layers n k [influence]\n"
      "N_LIST, K_LIST: comma-separated particles per side and neighbour counts";
  if (argc < 4) {
    std::cerr << usage << "\n";
    return 2;
  }
  Influence influence = Influence::inverse_square;
  if (argc > 4 && !parse_influence(argv[4], influence)) {
    std::cerr << "unknown influence " << argv[4] << "\n";
    return 2;
  }
  const std::string mode = argv[1];
  if (mode == "sweep") return sweep(parse_list(argv[2]), parse_list(argv[3]), influence);
  if (mode == "layers") return layers(std::stoi(argv[2]), std::stoi(argv[3]), influence);
  std::cerr << usage << "\n";
  return 2;
}

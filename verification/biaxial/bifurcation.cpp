// Is the uniform state of the biaxial specimen stable in the continuum? An independent check
// of the PD tangent's eigenvalues (docs/theory.md, "the uniform state loses stability").
//
// The half specimen [0, W] x [0, L] (plane strain, small strain) is in the uniform state of
// one material point driven through the seed's protocol (perinom::drive_biaxial). Its rate
// problem uses the consistent tangent C of that state everywhere (Hill's comparison solid):
//   -div(C : grad v) = lambda v,   v_x = 0 and shear-free at x = 0 (symmetry line),
//   traction rate zero at x = W (dead pressure), v_y = 0 and shear-free at y = 0 and y = L.
// C is coaxial with x and y, so the modes separate exactly: v_x = U(x) cos(k y),
// v_y = V(x) sin(k y), k = n pi / L. U and V are discretized by Chebyshev collocation in x
// (spectral: no PD, no mesh). An eigenvalue with negative real part means the uniform state
// is dynamically unstable, as a damped dynamics (ADR) sees it. The program prints, per load
// step of the compression stage, the smallest real part over n = 1 ... n_max, scaled by
// the elastic shear modulus times k^2 (so -1 ... 1 is comparable between modes).
//
// Usage: bifurcation [test 1-7] [W (m)] [L (m)] [chebyshev points] [n_max] [step]
// With a step, prints that step's scaled smallest real part for every mode n instead.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "perinom/materials/material_point.hpp"

namespace {

using Eigen::MatrixXd;

// In-plane tangent of plane strain: sigma_xx = c11 e_xx + c12 e_yy, sigma_yy = c21 e_xx +
// c22 e_yy, sigma_xy = c66 gamma_xy.
struct PlaneTangent {
  double c11, c12, c21, c22, c66;
  double coupling;  ///< largest |d sigma_xy / d e_xx|-type entry (0 when coaxial)
};

PlaneTangent plane_tangent(const double* D) {
  auto at = [D](int a, int b, int c, int e) { return D[((a * 3 + b) * 3 + c) * 3 + e]; };
  PlaneTangent t{at(0, 0, 0, 0), at(0, 0, 1, 1), at(1, 1, 0, 0), at(1, 1, 1, 1),
                 0.5 * (at(0, 1, 0, 1) + at(0, 1, 1, 0)), 0.0};
  t.coupling = std::max({std::abs(at(0, 1, 0, 0)), std::abs(at(0, 1, 1, 1)), std::abs(at(0, 0, 0, 1)),
                         std::abs(at(1, 1, 0, 1))});
  return t;
}

// Loss of ellipticity (shear bands): the smallest det of the acoustic tensor Q = n.C.n over
// directions n (coaxial C: a quarter turn suffices), scaled by c66^2 of the elastic law.
double smallest_acoustic_det(const PlaneTangent& C) {
  double worst = 1e300;
  for (int a = 0; a <= 900; ++a) {
    const double t = 0.5 * M_PI * a / 900, n1 = std::cos(t), n2 = std::sin(t);
    const double q11 = C.c11 * n1 * n1 + C.c66 * n2 * n2, q22 = C.c66 * n1 * n1 + C.c22 * n2 * n2;
    const double q12 = (C.c12 + C.c66) * n1 * n2, q21 = (C.c21 + C.c66) * n1 * n2;
    worst = std::min(worst, q11 * q22 - q12 * q21);
  }
  return worst;
}

// Chebyshev points on [0, w] (x_0 = w ... x_N = 0) and the first-derivative matrix
// (Trefethen, Spectral Methods in MATLAB, cheb.m, scaled to the interval).
void chebyshev(int N, double w, std::vector<double>& x, MatrixXd& D1) {
  x.resize(N + 1);
  std::vector<double> t(N + 1), c(N + 1);
  for (int j = 0; j <= N; ++j) {
    t[j] = std::cos(M_PI * j / N);
    c[j] = (j == 0 || j == N ? 2.0 : 1.0) * (j % 2 ? -1.0 : 1.0);
    x[j] = 0.5 * w * (t[j] + 1.0);
  }
  D1 = MatrixXd::Zero(N + 1, N + 1);
  for (int i = 0; i <= N; ++i) {
    for (int j = 0; j <= N; ++j)
      if (i != j) D1(i, j) = c[i] / c[j] / (t[i] - t[j]);
    for (int j = 0; j <= N; ++j)
      if (i != j) D1(i, i) -= D1(i, j);
  }
  D1 *= 2.0 / w;
}

// Smallest real part of the spectrum of the mode k (unknowns U_0..U_N, V_0..V_N; node 0 is
// x = W, node N is x = 0).
double smallest_real_part(const PlaneTangent& C, double k, const MatrixXd& D1) {
  const int n = static_cast<int>(D1.rows());
  const MatrixXd D2 = D1 * D1, I = MatrixXd::Identity(n, n);
  MatrixXd A(2 * n, 2 * n);
  // -(x equilibrium) and -(y equilibrium) of the separated modes.
  A.topLeftCorner(n, n) = -(C.c11 * D2 - C.c66 * k * k * I);
  A.topRightCorner(n, n) = -(C.c12 + C.c66) * k * D1;
  A.bottomLeftCorner(n, n) = (C.c21 + C.c66) * k * D1;
  A.bottomRightCorner(n, n) = -(C.c66 * D2 - C.c22 * k * k * I);
  // Boundary rows replace the equations at the end nodes.
  const int uW = 0, uO = n - 1, vW = n, vO = 2 * n - 1;
  A.row(uO).setZero();
  A(uO, uO) = 1.0;                                         // U(0) = 0
  A.row(vO).setZero();                                     // shear-free at x = 0: V' - k U = 0
  A.block(vO, n, 1, n) = D1.row(n - 1);
  A(vO, uO) -= k;
  A.row(uW).setZero();                                     // sigma_xx rate = 0 at x = W
  A.block(uW, 0, 1, n) = C.c11 * D1.row(0);
  A(uW, vW) += C.c12 * k;
  A.row(vW).setZero();                                     // shear-free at x = W
  A.block(vW, n, 1, n) = D1.row(0);
  A(vW, uW) -= k;
  // Eliminate the four boundary values: A_bb x_b + A_bi x_i = 0.
  const std::vector<int> b = {uW, uO, vW, vO};
  std::vector<int> in;
  for (int r = 0; r < 2 * n; ++r)
    if (r != uW && r != uO && r != vW && r != vO) in.push_back(r);
  auto pick = [&](const std::vector<int>& rows, const std::vector<int>& cols) {
    MatrixXd M(rows.size(), cols.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t j = 0; j < cols.size(); ++j) M(i, j) = A(rows[i], cols[j]);
    return M;
  };
  const MatrixXd reduced = pick(in, in) - pick(in, b) * pick(b, b).lu().solve(pick(b, in));
  return Eigen::EigenSolver<MatrixXd>(reduced, false).eigenvalues().real().minCoeff();
}

}  // namespace

int main(int argc, char** argv) {
  const int test = argc > 1 ? std::atoi(argv[1]) : 2;
  const double W = argc > 2 ? std::atof(argv[2]) : 0.025, L = argc > 3 ? std::atof(argv[3]) : 0.1;
  const int N = argc > 4 ? std::atoi(argv[4]) : 40, n_max = argc > 5 ? std::atoi(argv[5]) : 20;
  const int only_step = argc > 6 ? std::atoi(argv[6]) : -1;
  const perinom::BiaxialTest t = perinom::seed_biaxial_test(test);
  const auto path = perinom::drive_biaxial(t.material, t.protocol);
  std::vector<double> x;
  MatrixXd D1;
  chebyshev(N, W, x, D1);
  const double G = t.material.shear();
  std::printf("# biaxial test %d, half specimen %g x %g m, %d Chebyshev points, modes n = 1 ... %d\n", test, W, L,
              N + 1, n_max);
  std::printf("step,eps_yy,min_real_part_scaled,critical_n,mode1_real_part_scaled,acoustic_det_scaled,c11,c12,c21,c22,c66,coupling\n");
  const int first = t.protocol.consolidation_steps;
  for (std::size_t s = first; s < path.size(); ++s) {
    if (only_step >= 0 && static_cast<int>(s) != only_step) continue;
    double D[81];
    perinom::DruckerPrager::State out;
    const auto& from = path[s == 0 ? 0 : s - 1];
    const double deps[9] = {path[s].eps_xx - from.eps_xx, 0, 0, 0, path[s].eps_yy - from.eps_yy, 0, 0, 0, 0};
    t.material.tangent(from.state, deps, out, D);
    const PlaneTangent C = plane_tangent(D);
    double worst = 1e300, mode1 = 0.0;
    int worst_n = 0;
    for (int m = 1; m <= n_max; ++m) {
      const double k = m * M_PI / L;
      const double r = smallest_real_part(C, k, D1) / (G * k * k);
      if (only_step >= 0) std::printf("# mode n = %d: %.6e\n", m, r);
      if (r < worst) worst = r, worst_n = m;
      if (m == 1) mode1 = r;
    }
    std::printf("%zu,%.6e,%.6e,%d,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.1e\n", s, path[s].eps_yy, worst, worst_n, mode1, smallest_acoustic_det(C) / (G * G), C.c11, C.c12,
                C.c21, C.c22, C.c66, C.coupling);
  }
  return 0;
}

#include "perinom/models/rigid_body.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

std::array<double, 3> centroid(const PointCloud& cloud) {
  const int d = cloud.dim;
  std::array<double, 3> c{0, 0, 0};
  double volume = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (int a = 0; a < d; ++a) c[a] += cloud.volume[i] * cloud.x[i * d + a];
    volume += cloud.volume[i];
  }
  for (int a = 0; a < d; ++a) c[a] /= volume;
  return c;
}

ParticleId nearest(const PointCloud& cloud, const std::array<double, 3>& p) {
  const int d = cloud.dim;
  double best = INFINITY;
  ParticleId arg = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    double r2 = 0.0;
    for (int a = 0; a < d; ++a) r2 += (cloud.x[i * d + a] - p[a]) * (cloud.x[i * d + a] - p[a]);
    if (r2 < best) best = r2, arg = static_cast<ParticleId>(i);
  }
  return arg;
}

/// The smallest pivot of Gaussian elimination with partial pivoting on the m x m matrix A.
double smallest_pivot(std::vector<double> A, int m) {
  double smallest = INFINITY;
  for (int k = 0; k < m; ++k) {
    int p = k;
    for (int r = k + 1; r < m; ++r)
      if (std::abs(A[r * m + k]) > std::abs(A[p * m + k])) p = r;
    for (int c = 0; c < m; ++c) std::swap(A[k * m + c], A[p * m + c]);
    smallest = std::min(smallest, std::abs(A[k * m + k]));
    if (A[k * m + k] == 0.0) return 0.0;
    for (int r = k + 1; r < m; ++r) {
      const double f = A[r * m + k] / A[k * m + k];
      for (int c = k; c < m; ++c) A[r * m + c] -= f * A[k * m + c];
    }
  }
  return smallest;
}

}  // namespace

bool LoadResultant::balanced(double tolerance) const {
  const double f = std::hypot(force[0], force[1], force[2]);
  const double m = std::hypot(moment[0], moment[1], moment[2]);
  return f <= tolerance * force_scale && m <= tolerance * force_scale * length;
}

LoadResultant load_resultant(const PointCloud& cloud, const std::vector<double>& force) {
  const int d = cloud.dim;
  LoadResultant r;
  r.about = centroid(cloud);
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < cloud.size(); ++i)
    for (int a = 0; a < d; ++a) lo[a] = std::min(lo[a], cloud.x[i * d + a]), hi[a] = std::max(hi[a], cloud.x[i * d + a]);
  for (int a = 0; a < d; ++a) r.length += (hi[a] - lo[a]) * (hi[a] - lo[a]);
  r.length = std::sqrt(r.length);
  if (force.empty()) return r;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    std::array<double, 3> x{0, 0, 0}, f{0, 0, 0};
    for (int a = 0; a < d; ++a) x[a] = cloud.x[i * d + a] - r.about[a], f[a] = force[i * d + a];
    for (int a = 0; a < d; ++a) r.force[a] += f[a];
    r.force_scale += std::hypot(f[0], f[1], f[2]);
    // 2-D: the z moment, stored first.
    if (d == 2) {
      r.moment[0] += x[0] * f[1] - x[1] * f[0];
    } else {
      r.moment[0] += x[1] * f[2] - x[2] * f[1];
      r.moment[1] += x[2] * f[0] - x[0] * f[2];
      r.moment[2] += x[0] * f[1] - x[1] * f[0];
    }
  }
  return r;
}

std::vector<RigidBodyPin> rigid_body_pins(const PointCloud& cloud) {
  const int d = cloud.dim;
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < cloud.size(); ++i)
    for (int a = 0; a < d; ++a) lo[a] = std::min(lo[a], cloud.x[i * d + a]), hi[a] = std::max(hi[a], cloud.x[i * d + a]);
  // Axes by decreasing extent (a stable order on ties: x before y before z).
  std::array<int, 3> axis{0, 1, 2};
  std::stable_sort(axis.begin(), axis.begin() + d, [&](int a, int b) { return hi[a] - lo[a] > hi[b] - lo[b]; });
  const ParticleId A = nearest(cloud, centroid(cloud));
  // The far end of an axis through A: the particle nearest A moved to the farther box end.
  auto far_end = [&](int e) {
    std::array<double, 3> p{0, 0, 0};
    for (int a = 0; a < d; ++a) p[a] = cloud.x[A * d + a];
    p[e] = hi[e] - p[e] >= p[e] - lo[e] ? hi[e] : lo[e];
    return nearest(cloud, p);
  };
  std::vector<RigidBodyPin> pins;
  pins.push_back({A, {}});
  for (int a = 0; a < d; ++a) pins[0].components.push_back(a);
  if (d == 2) {
    pins.push_back({far_end(axis[0]), {axis[1]}});
  } else {
    pins.push_back({far_end(axis[0]), {std::min(axis[1], axis[2]), std::max(axis[1], axis[2])}});
    pins.push_back({far_end(axis[1]), {axis[2]}});
  }
  // The pinned values of the rigid modes (translations, then rotations over the body's size):
  // square and regular exactly when the pins remove every rigid mode and no more.
  const int m = d * (d + 1) / 2;
  double L = 0.0;
  for (int a = 0; a < d; ++a) L = std::max(L, hi[a] - lo[a]);
  std::vector<double> M;
  for (const auto& pin : pins)
    for (const int c : pin.components) {
      const double* x = cloud.point(pin.particle);
      std::vector<double> row(m, 0.0);
      row[c] = 1.0;
      if (L > 0.0) {
        // u = w x r (r from the origin A): rotation about z moves x by -w y and y by w x.
        const double* xa = cloud.point(A);
        std::array<double, 3> r{0, 0, 0};
        for (int a = 0; a < d; ++a) r[a] = (x[a] - xa[a]) / L;
        if (d == 2) {
          row[2] = c == 0 ? -r[1] : r[0];
        } else {
          // columns 3, 4, 5: rotations about x, y, z; the entries are (w x r)_c.
          if (c == 0) row[4] = r[2], row[5] = -r[1];
          if (c == 1) row[3] = -r[2], row[5] = r[0];
          if (c == 2) row[3] = r[1], row[4] = -r[0];
        }
      }
      M.insert(M.end(), row.begin(), row.end());
    }
  if (!(L > 0.0) || smallest_pivot(M, m) < 1e-3)
    throw InputError("the pins do not determine the body's rigid motion (the body is too small or too thin for them)");
  return pins;
}

}  // namespace perinom

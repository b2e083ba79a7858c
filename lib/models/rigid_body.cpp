#include "perinom/models/rigid_body.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Dense>

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

/// The volume centroid and the bounding-box diagonal of the particles flagged in `within`
/// (empty: all).
struct Extent {
  std::array<double, 3> about{0, 0, 0};
  double length = 0.0;
};
Extent extent(const PointCloud& cloud, const std::vector<std::uint8_t>& within = {}) {
  const int d = cloud.dim;
  Extent e;
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  double volume = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!within.empty() && !within[i]) continue;
    for (int a = 0; a < d; ++a) {
      const double x = cloud.x[i * d + a];
      e.about[a] += cloud.volume[i] * x, lo[a] = std::min(lo[a], x), hi[a] = std::max(hi[a], x);
    }
    volume += cloud.volume[i];
  }
  for (int a = 0; a < d; ++a) e.about[a] /= volume, e.length += (hi[a] - lo[a]) * (hi[a] - lo[a]);
  e.length = std::sqrt(e.length);
  return e;
}

std::array<double, 3> centroid(const PointCloud& cloud) { return extent(cloud).about; }

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

/// Component c of the d (d + 1) / 2 rigid modes at x: translations, then rotations about
/// `origin` over the length L (u = w x r, r = (x - origin) / L; in 2-D the rotation about z
/// moves x by -w y and y by w x; in 3-D columns 3, 4, 5 turn about x, y, z). L = 0: the
/// translations only.
std::vector<double> rigid_mode_row(const double* x, const double* origin, double L, int c, int d) {
  std::vector<double> row(static_cast<std::size_t>(d * (d + 1) / 2), 0.0);
  row[c] = 1.0;
  if (!(L > 0.0)) return row;
  std::array<double, 3> r{0, 0, 0};
  for (int a = 0; a < d; ++a) r[a] = (x[a] - origin[a]) / L;
  if (d == 2) {
    row[2] = c == 0 ? -r[1] : r[0];
  } else {
    if (c == 0) row[4] = r[2], row[5] = -r[1];
    if (c == 1) row[3] = -r[2], row[5] = r[0];
    if (c == 2) row[3] = r[1], row[4] = -r[0];
  }
  return row;
}

}  // namespace

bool LoadResultant::balanced(double tolerance) const {
  const double f = std::hypot(force[0], force[1], force[2]);
  const double m = std::hypot(moment[0], moment[1], moment[2]);
  return f <= tolerance * force_scale && m <= tolerance * force_scale * length;
}

LoadResultant load_resultant(const PointCloud& cloud, const std::vector<double>& force) {
  LoadResultant whole;
  const Extent e = extent(cloud);
  whole.about = e.about, whole.length = e.length;
  return load_resultant_part(cloud, force, force.empty() ? 0 : cloud.size(), whole);
}

LoadResultant load_resultant_part(const PointCloud& cloud, const std::vector<double>& force, std::size_t count,
                                  const LoadResultant& whole) {
  const int d = cloud.dim;
  LoadResultant r;
  r.about = whole.about, r.length = whole.length;
  for (std::size_t i = 0; i < count; ++i) {
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
      const std::vector<double> row = rigid_mode_row(cloud.point(pin.particle), cloud.point(A), L, c, d);
      M.insert(M.end(), row.begin(), row.end());
    }
  if (!(L > 0.0) || smallest_pivot(M, m) < 1e-3)
    throw InputError("the pins do not determine the body's rigid motion (the body is too small or too thin for them)");
  return pins;
}

namespace {

/// The combinations of m modes that every row reads as zero: a basis, from the Gram matrix
/// of the rows (each the m modes' values a constraint reads). A held combination moves some
/// row by a lever over the body's size; rounding leaves a free one near 1e-16 of the largest
/// eigenvalue.
std::vector<Eigen::VectorXd> unread(int m, const std::vector<Eigen::VectorXd>& rows) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(m, m);
  for (const Eigen::VectorXd& a : rows) G += a * a.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G);
  const double floor = 1e-10 * std::max(1.0, eig.eigenvalues().maxCoeff());
  std::vector<Eigen::VectorXd> out;
  for (int e = 0; e < m; ++e)
    if (eig.eigenvalues()[e] <= floor) out.push_back(eig.eigenvectors().col(e));
  return out;
}

/// What the loading's constraint k reads of the modes mode(dof): u[fixed] / scale + sum_c
/// coef[c] u[coupled[c]] for a face-located one, u[fixed] for one at its particle.
template <class Mode>
Eigen::VectorXd constraint_row(const Loading& loading, std::size_t k, const Mode& mode) {
  Eigen::VectorXd a = mode(loading.fixed[k]);
  if (!loading.couplings.empty() && loading.couplings[k + 1] > loading.couplings[k]) {
    a /= loading.scale[k];
    for (Offset c = loading.couplings[k]; c < loading.couplings[k + 1]; ++c) a += loading.coef[c] * mode(loading.coupled[c]);
  }
  return a;
}

/// A free motion t + w x (x - c) from its translation and rotation: a turn when w's lever
/// over the body's size L is not negligible against t, about the axis through the points whose
/// velocity is along w, x = c + w x t / |w|^2.
FreeRigidMotion motion(const std::array<double, 3>& t, const std::array<double, 3>& w, const std::array<double, 3>& c,
                       double L, int d) {
  FreeRigidMotion f;
  f.translation = t, f.rotation = w, f.point = c;
  const double t2 = t[0] * t[0] + t[1] * t[1] + t[2] * t[2], ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  f.turns = ww * L * L > 1e-12 * t2;
  if (f.turns) {
    f.point[0] += (w[1] * t[2] - w[2] * t[1]) / ww;
    f.point[1] += (w[2] * t[0] - w[0] * t[2]) / ww;
    f.point[2] += (w[0] * t[1] - w[1] * t[0]) / ww;
    if (d == 2) f.point[2] = 0.0;
  }
  return f;
}

}  // namespace

std::vector<FreeRigidMotion> free_rigid_motions(const PointCloud& cloud, const Loading& loading,
                                               const std::vector<std::uint8_t>& within) {
  const int d = cloud.dim;
  const int m = d * (d + 1) / 2;
  auto in = [&](std::int64_t dof) { return within.empty() || within[static_cast<std::size_t>(dof / d)]; };
  // The rotations turn about the part's centroid, over its size (one particle: any length).
  const Extent part = extent(cloud, within);
  const double L = part.length > 0.0 ? part.length : 1.0;
  auto mode = [&](std::int64_t dof) {
    const std::vector<double> row =
        rigid_mode_row(cloud.point(static_cast<std::size_t>(dof / d)), part.about.data(), L, static_cast<int>(dof % d), d);
    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(row.data(), m));
  };
  std::vector<Eigen::VectorXd> rows;
  for (std::size_t k = 0; k < loading.fixed.size(); ++k)
    if (in(loading.fixed[k])) rows.push_back(constraint_row(loading, k, mode));
  std::vector<FreeRigidMotion> out;
  for (const Eigen::VectorXd& v : unread(m, rows)) {
    std::array<double, 3> t{0, 0, 0}, w{0, 0, 0};
    for (int a = 0; a < d; ++a) t[a] = v[a];
    for (int a = 0; a < (d == 2 ? 1 : 3); ++a) w[d == 2 ? 2 : a] = v[d + a] / L;
    out.push_back(motion(t, w, part.about, L, d));
  }
  return out;
}

std::vector<FreeRigidMotion> free_plate_motions(const PlateCloud& plate, const Loading& loading) {
  // The plate's rigid deflections w = t + w_x (y - c_y) - w_y (x - c_x), the z velocity of a
  // motion t e_z + w x (x - c) with w in the plane; modes (1, (y - c_y) / L, -(x - c_x) / L).
  PointCloud nodes = plate.cloud;
  nodes.x.resize(2 * plate.physical), nodes.volume.resize(plate.physical);
  const Extent part = extent(nodes);
  const double L = part.length > 0.0 ? part.length : 1.0;
  auto at = [&](std::size_t p) {
    const double* x = &plate.cloud.x[2 * p];
    return Eigen::Vector3d(1.0, (x[1] - part.about[1]) / L, -(x[0] - part.about[0]) / L);
  };
  auto mode = [&](std::int64_t dof) { return Eigen::VectorXd(at(static_cast<std::size_t>(dof))); };
  std::vector<Eigen::VectorXd> rows;
  for (std::size_t k = 0; k < loading.fixed.size(); ++k) rows.push_back(constraint_row(loading, k, mode));
  // A ghost holds w_ghost = sign w_image: a mode the mirror does not continue (a clamped
  // edge's turn about itself) is held.
  for (std::size_t g = 0; g < plate.image.size(); ++g)
    rows.push_back(at(plate.physical + g) - plate.sign[g] * at(static_cast<std::size_t>(plate.image[g])));
  std::vector<FreeRigidMotion> out;
  for (const Eigen::VectorXd& v : unread(3, rows))
    out.push_back(motion({0.0, 0.0, v[0]}, {v[1] / L, v[2] / L, 0.0}, {part.about[0], part.about[1], 0.0}, L, 3));
  return out;
}

}  // namespace perinom

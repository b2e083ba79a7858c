#include "perinom/operators/bond_weights.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "perinom/operators/singular_family.hpp"
#include "shape_tensor.hpp"

namespace perinom {

bool shape_tensor(int d, const double* x, std::size_t i, Offset begin, Offset end, const ParticleId* col,
                  const double* wv, const std::uint8_t* alive, double* Kout, double* Kinv_out) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(d, d);
  const double* xi_i = x + i * d;
  for (Offset k = begin; k < end; ++k) {
    if (alive && !alive[k]) continue;
    const std::size_t j = col[k];
    Eigen::VectorXd xi(d);
    for (int a = 0; a < d; ++a) xi[a] = x[j * d + a] - xi_i[a];
    K.noalias() += wv[k] * xi * xi.transpose();
  }
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) Kout[r * d + c] = K(r, c), Kinv_out[r * d + c] = 0.0;
  // A family that does not span R^d has a (near) zero eigenvalue relative to the largest.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, Eigen::EigenvaluesOnly);
  const double lmax = eig.eigenvalues().maxCoeff(), lmin = eig.eigenvalues().minCoeff();
  if (!(lmax > 0.0) || lmin <= 1e-10 * lmax) return false;
  const Eigen::MatrixXd Kinv = K.inverse();
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) Kinv_out[r * d + c] = Kinv(r, c);
  return true;
}

double shape_quality(int d, const double* K) {
  double tr = 0.0;
  for (int a = 0; a < d; ++a) tr += K[a * d + a];
  if (!(tr > 0.0)) return 0.0;
  const double det = d == 2 ? K[0] * K[3] - K[1] * K[2]
                            : K[0] * (K[4] * K[8] - K[5] * K[7]) - K[1] * (K[3] * K[8] - K[5] * K[6]) +
                                  K[2] * (K[3] * K[7] - K[4] * K[6]);
  return det / std::pow(tr / d, d);
}

BondWeights bond_weights(const PointCloud& cloud, const Families& families, Influence kind,
                         std::size_t checked_rows) {
  const int d = cloud.dim;
  const std::size_t n = cloud.size();
  BondWeights b;
  b.wv.resize(families.bonds());
  b.shape.assign(n * d * d, 0.0);
  b.shape_inverse.assign(n * d * d, 0.0);
  long singular = -1;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    const double* xi_i = cloud.point(i);
    for (Offset k = families.begin(i); k < families.end(i); ++k) {
      const ParticleId j = families.neighbors[k];
      Eigen::VectorXd xi(d);
      for (int a = 0; a < d; ++a) xi[a] = cloud.x[j * d + a] - xi_i[a];
      b.wv[k] = influence(kind, xi.norm(), families.support[i]) * cloud.volume[j];
    }
    if (!shape_tensor(d, cloud.x.data(), i, families.begin(i), families.end(i), families.neighbors.data(),
                      b.wv.data(), nullptr, b.shape.data() + i * d * d, b.shape_inverse.data() + i * d * d) &&
        i < checked_rows) {
#pragma omp critical
      if (singular < 0 || static_cast<long>(i) < singular) singular = static_cast<long>(i);
    }
  }
  if (singular >= 0)
    throw SingularFamily(d, cloud.x.data(), static_cast<ParticleId>(singular),
                         static_cast<long>(families.end(singular) - families.begin(singular)), 1);
  return b;
}

}  // namespace perinom

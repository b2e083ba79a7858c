#include "perinom/operators/bond_weights.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "perinom/core/error.hpp"

namespace perinom {

BondWeights bond_weights(const PointCloud& cloud, const Families& families, Influence kind) {
  const int d = cloud.dim;
  const std::size_t n = cloud.size();
  BondWeights b;
  b.wv.resize(families.bonds());
  b.shape.assign(n * d * d, 0.0);
  b.shape_inverse.assign(n * d * d, 0.0);
  long singular = -1;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(d, d);
    const double* xi_i = cloud.point(i);
    for (Offset k = families.begin(i); k < families.end(i); ++k) {
      const ParticleId j = families.neighbors[k];
      Eigen::VectorXd xi(d);
      for (int a = 0; a < d; ++a) xi[a] = cloud.x[j * d + a] - xi_i[a];
      const double wv = influence(kind, xi.norm(), families.support[i]) * cloud.volume[j];
      b.wv[k] = wv;
      K.noalias() += wv * xi * xi.transpose();
    }
    // A family that does not span R^d has a (near) zero eigenvalue relative to the largest.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, Eigen::EigenvaluesOnly);
    const double lmax = eig.eigenvalues().maxCoeff(), lmin = eig.eigenvalues().minCoeff();
    if (!(lmax > 0.0) || lmin <= 1e-10 * lmax) {
#pragma omp critical
      if (singular < 0 || static_cast<long>(i) < singular) singular = static_cast<long>(i);
      continue;
    }
    const Eigen::MatrixXd Kinv = K.inverse();
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c) {
        b.shape[i * d * d + r * d + c] = K(r, c);
        b.shape_inverse[i * d * d + r * d + c] = Kinv(r, c);
      }
  }
  if (singular >= 0) {
    std::ostringstream msg;
    msg << "particle " << singular << " at (";
    for (int a = 0; a < d; ++a) msg << (a ? ", " : "") << cloud.x[singular * d + a];
    msg << "): shape tensor is singular; its family of "
        << families.end(singular) - families.begin(singular)
        << " neighbours does not span R^" << d
        << " (increase discretization.horizon.ratio or discretization.horizon.neighbors)";
    throw InputError(msg.str());
  }
  return b;
}

}  // namespace perinom

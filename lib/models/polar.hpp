#pragma once
// The rotation of a polar decomposition and its derivative (internal to lib/models).
#include <Eigen/Dense>

namespace perinom::detail {

using Mat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

/// R of F = R U (det F > 0).
inline Mat3 rotation(const Mat3& F) {
  const Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

/// dR for a change dF of F = R U: dR = R [w]x with (tr(U) I - U) w = axial(R^T dF - dF^T R),
/// since R^T dF - dF^T R = W U + U W = [(tr(U) I - U) w]x for W = R^T dR skew.
inline Mat3 rotation_derivative(const Mat3& R, const Mat3& U, const Mat3& dF) {
  const Mat3 A = R.transpose() * dF - dF.transpose() * R;
  const Eigen::Vector3d axial(A(2, 1), A(0, 2), A(1, 0));
  const Eigen::Vector3d w = (U.trace() * Mat3::Identity() - U).lu().solve(axial);
  Mat3 W;
  W << 0.0, -w(2), w(1), w(2), 0.0, -w(0), -w(1), w(0), 0.0;
  return R * W;
}

}  // namespace perinom::detail

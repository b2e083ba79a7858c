// The consistent tangent dP/dH of FiniteRotationLaw, in closed form: the chain rule through
// every step of the update (the midpoint increment, the wrapped law's return map, the
// rotation to Cauchy stress and P = J sigma F^-T), one direction dH per column.
#include "perinom/models/finite_rotation.hpp"

#include "polar.hpp"

namespace perinom {

using detail::Mat3;

void FiniteRotationLaw::tangent(std::size_t i, const double* H, double* C) const {
  const int d = dim_;
  Mat3 F = Mat3::Identity();
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) F(a, b) += H[a * d + b];
  const Mat3 Fn = Eigen::Map<const Mat3>(committed_F_.data() + i * 9);
  const Mat3 Fm = 0.5 * (F + Fn), Fm_inv = Fm.inverse();
  const Mat3 L = (F - Fn) * Fm_inv, S = 0.5 * (L + L.transpose());
  const Mat3 Rm = detail::rotation(Fm), Um = Rm.transpose() * Fm;
  const Mat3 deps = Rm.transpose() * S * Rm;
  // The law: the unrotated stress and its tangent D = d sigma_u / d deps.
  double D[81], sigma_u_data[9];
  law_->tangent(i, deps.data(), sigma_u_data, D);
  const Mat3 sigma_u = Eigen::Map<const Mat3>(sigma_u_data);
  const Mat3 R = detail::rotation(F), U = R.transpose() * F;
  const Mat3 F_inv = F.inverse(), F_invT = F_inv.transpose();
  const double J = F.determinant();
  const Mat3 sigma = R * sigma_u * R.transpose();
  for (int c = 0; c < d; ++c)
    for (int e = 0; e < d; ++e) {
      Mat3 dF = Mat3::Zero();
      dF(c, e) = 1.0;
      // The strain increment R_m^T sym(L) R_m, L = (F - F_n) F_m^-1, F_m = (F + F_n) / 2.
      const Mat3 dFm = 0.5 * dF;
      const Mat3 dL = dF * Fm_inv - (F - Fn) * Fm_inv * dFm * Fm_inv;
      const Mat3 dS = 0.5 * (dL + dL.transpose());
      const Mat3 dRm = detail::rotation_derivative(Rm, Um, dFm);
      const Mat3 ddeps = dRm.transpose() * S * Rm + Rm.transpose() * dS * Rm + Rm.transpose() * S * dRm;
      // The unrotated stress, then the Cauchy stress R sigma_u R^T.
      Mat3 dsigma_u = Mat3::Zero();
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q)
          for (int r = 0; r < 3; ++r)
            for (int t = 0; t < 3; ++t) dsigma_u(p, q) += D[((p * 3 + q) * 3 + r) * 3 + t] * ddeps(r, t);
      const Mat3 dR = detail::rotation_derivative(R, U, dF);
      const Mat3 dsigma = dR * sigma_u * R.transpose() + R * dsigma_u * R.transpose() + R * sigma_u * dR.transpose();
      // P = J sigma F^-T.
      const double dJ = J * (F_inv * dF).trace();
      const Mat3 dF_invT = -(F_inv * dF * F_inv).transpose();
      const Mat3 dP = dJ * sigma * F_invT + J * dsigma * F_invT + J * sigma * dF_invT;
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b) C[((a * d + b) * d + c) * d + e] = dP(a, b);
    }
}

}  // namespace perinom

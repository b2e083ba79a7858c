#include "perinom/operators/hourglass_energy.hpp"

#include <stdexcept>

#include "operator_access.hpp"

namespace perinom {

std::vector<double> hourglass_energy_density(const NonlocalOperator& G, const double* u, double modulus) {
  const std::vector<double>& x = OperatorAccess::positions(G);
  const std::vector<double>& wv = OperatorAccess::wv(G);
  if (G.order() != 1 || x.empty())
    throw std::invalid_argument("hourglass_energy_density: needs a first-order G built from a fit");
  const int d = G.dim();
  const BondGraph& g = G.graph();
  const std::size_t n = G.rows();
  std::vector<double> H(n * d * d), psi(n, 0.0);
  G.apply(u, d, H.data());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (G.is_detached(i)) continue;
    const double* K = G.shape(i);
    double tr = 0.0;
    for (int a = 0; a < d; ++a) tr += K[a * d + a];
    if (!(tr > 0.0)) continue;
    double s = 0.0;
    for (Offset k = g.begin(i); k < g.end(i); ++k) {
      if (!g.alive(k)) continue;
      double l2;
      s += wv[k] * hourglass_z2(d, x.data(), u, H.data(), i, g.col(k), l2);
    }
    psi[i] = 0.5 * modulus / tr * s;
  }
  return psi;
}

}  // namespace perinom

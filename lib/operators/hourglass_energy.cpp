#include "perinom/operators/hourglass_energy.hpp"

#include <stdexcept>
#include <string>

#include "operator_access.hpp"

namespace perinom {

namespace {

const char* check(const NonlocalOperator& G) {
  return G.order() != 1 || OperatorAccess::positions(G).empty() ? "needs a first-order G built from a fit" : nullptr;
}

}  // namespace

double hourglass_row(const NonlocalOperator& G, const double* u, const double* H, std::size_t i, double modulus,
                     double volume, double sign, double* f) {
  if (const char* what = check(G)) throw std::invalid_argument(std::string("hourglass_row: ") + what);
  if (G.is_detached(i)) return 0.0;
  const int d = G.dim();
  const double* K = G.shape(i);
  double tr = 0.0;
  for (int a = 0; a < d; ++a) tr += K[a * d + a];
  if (!(tr > 0.0)) return 0.0;
  const double* x = OperatorAccess::positions(G).data();
  const std::vector<double>& wv = OperatorAccess::wv(G);
  const BondGraph& g = G.graph();
  const double c = modulus / tr, scale = sign * c * volume;
  double s = 0.0, z[3], l2;
  for (Offset k = g.begin(i); k < g.end(i); ++k) {
    if (!g.alive(k)) continue;
    const std::size_t j = g.col(k);
    hourglass_z(d, x, u, H, i, j, z, l2);
    for (int a = 0; a < d; ++a) {
      s += wv[k] * z[a] * z[a];
      if (f) f[j * d + a] += scale * wv[k] * z[a], f[i * d + a] -= scale * wv[k] * z[a];
    }
  }
  return 0.5 * c * s;
}

std::vector<double> hourglass_energy_density(const NonlocalOperator& G, const double* u, double modulus) {
  if (const char* what = check(G)) throw std::invalid_argument(std::string("hourglass_energy_density: ") + what);
  const int d = G.dim();
  const std::size_t n = G.rows();
  std::vector<double> H(n * d * d), psi(n, 0.0);
  G.apply(u, d, H.data());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) psi[i] = hourglass_row(G, u, H.data(), i, modulus, 1.0, 1.0, nullptr);
  return psi;
}

}  // namespace perinom

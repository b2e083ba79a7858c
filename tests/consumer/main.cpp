// Links perinom through find_package and computes one gradient: exact for a linear field.
#include <cmath>
#include <cstdio>

#include "perinom/geometry/lattice.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/operators/nonlocal_operator.hpp"

int main() {
  using namespace perinom;
  BoxGeometry box;
  box.dim = 2;
  box.max = {1.0, 1.0, 0.0};
  const PointCloud cloud = make_lattice(box, 0.1);
  const Families families = radius_families(cloud, 0.3015);
  const NonlocalOperator G(cloud, families, bond_weights(cloud, families, Influence::constant));
  std::vector<double> f(cloud.size()), grad(cloud.size() * 2);
  for (std::size_t i = 0; i < cloud.size(); ++i) f[i] = 2.0 * cloud.x[2 * i] - cloud.x[2 * i + 1];
  G.apply(f.data(), 1, grad.data());
  const double err = std::abs(grad[0] - 2.0) + std::abs(grad[1] + 1.0);
  std::printf("consumer: %zu particles, gradient error %.2e\n", cloud.size(), err);
  return err < 1e-12 ? 0 : 1;
}

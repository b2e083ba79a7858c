#include "perinom/materials/material_point.hpp"

#include <cmath>
#include <stdexcept>

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

// Advances `rec` by one step. Unknown increments: d[0] (eps_xx) always, d[1] (eps_yy) when
// its stress is held (hold_y); otherwise d[1] = dyy is prescribed.
void mixed_step(const DruckerPrager& dp, int substeps, double sxx, bool hold_y, double syy_or_dyy,
                MaterialPointRecord& rec) {
  double d[2] = {0.0, hold_y ? 0.0 : syy_or_dyy};
  const int unknowns = hold_y ? 2 : 1;
  DruckerPrager::State out;
  auto residual = [&](const double* dd, double* r) {
    const double deps[9] = {dd[0], 0, 0, 0, dd[1], 0, 0, 0, 0};
    if (substeps > 0) dp.update_substepped(rec.state, deps, substeps, out);
    else dp.update(rec.state, deps, out);
    r[0] = out.sigma[0] - sxx;
    r[1] = hold_y ? out.sigma[4] - syy_or_dyy : 0.0;
  };
  const double eps = 1e-9;
  double r[2];
  for (int it = 0; it < 50; ++it) {
    residual(d, r);
    if (std::abs(r[0]) + std::abs(r[1]) < 1e-6) break;
    double J[2][2] = {{1.0, 0.0}, {0.0, 1.0}};
    for (int c = 0; c < unknowns; ++c) {
      double dd[2] = {d[0], d[1]}, rp[2];
      dd[c] += eps;
      residual(dd, rp);
      for (int k = 0; k < unknowns; ++k) J[k][c] = (rp[k] - r[k]) / eps;
    }
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    if (det == 0.0) throw SolveError("material point: the mixed control lost its stiffness");
    const double s0 = (J[1][1] * r[0] - J[0][1] * r[1]) / det, s1 = (J[0][0] * r[1] - J[1][0] * r[0]) / det;
    d[0] -= s0;
    if (hold_y) d[1] -= s1;
  }
  residual(d, r);
  if (!(std::abs(r[0]) + std::abs(r[1]) < 1e-3))
    throw SolveError("material point: the held stresses were not reached (the point cannot carry them)");
  rec.state = out;
  rec.eps_xx += d[0];
  rec.eps_yy += d[1];
}

}  // namespace

BiaxialTest seed_biaxial_test(int test) {
  struct Row {
    double confining, h, d0;
  };
  constexpr Row table2[7] = {{400e3, 0, 0}, {600e3, 0, 0}, {800e3, 0, 0}, {1000e3, 0, 0},
                             {600e3, 25, 0}, {600e3, 50, 0}, {600e3, 0, 1}};
  if (test < 1 || test > 7) throw std::out_of_range("seed 000 Table 2 has tests 1 ... 7");
  const Row& r = table2[test - 1];
  BiaxialTest t;
  t.material.E = 30e6;
  t.material.nu = 0.25;
  t.material.friction_angle = 35.0 * M_PI / 180.0;
  t.material.cohesion = 60e3;
  t.material.m0 = 0.2;
  t.material.h = r.h;
  t.material.d0 = r.d0;
  t.protocol.confining = r.confining;
  return t;
}

std::vector<MaterialPointRecord> drive_biaxial(const DruckerPrager& dp, const BiaxialProtocol& p, int substeps) {
  std::vector<MaterialPointRecord> records(1);
  MaterialPointRecord rec;
  for (int k = 1; k <= p.consolidation_steps; ++k) {
    const double s = -p.confining * k / p.consolidation_steps;
    mixed_step(dp, substeps, s, true, s, rec);
    records.push_back(rec);
  }
  for (int k = 1; k <= p.compression_steps; ++k) {
    mixed_step(dp, substeps, -p.confining, false, -p.vertical_strain / p.compression_steps, rec);
    records.push_back(rec);
  }
  return records;
}

}  // namespace perinom

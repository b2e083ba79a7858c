// perinom bench force: times the explicit force evaluation (G product, pointwise law,
// transposed product, and the stabilization product) on an n^d simple-cubic lattice with
// horizon ratio 3.015, measures this machine's STREAM-triad bandwidth, and ends with one
// JSON object on the last line.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "commands.hpp"
#include "perinom/core/error.hpp"
#include "perinom/core/timer.hpp"
#include "perinom/geometry/lattice.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/operators/scalar_csr.hpp"

namespace perinom::cli {
namespace {

/// Best-of-5 STREAM triad a = b + s c over arrays far larger than the caches (GB/s).
double stream_triad_gbs() {
  const std::size_t n = 20'000'000;
  std::vector<double> a(n), b(n, 1.0), c(n, 2.0);
  double best = 1e300;
  for (int rep = 0; rep < 5; ++rep) {
    const double t0 = wall_seconds();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + 3.0 * c[i];
    best = std::min(best, wall_seconds() - t0);
  }
  return 3.0 * sizeof(double) * n / best / 1e9 + 0.0 * a[n / 2];
}

}  // namespace

int bench(const Options& opt) {
  if (opt.positional.size() != 1 || opt.positional[0] != "force")
    throw InputError("bench: the only benchmark is 'force'");
  if (opt.dimension != 2 && opt.dimension != 3) throw InputError("--dimension must be 2 or 3");
  if (opt.n < 4) throw InputError("--n must be at least 4");
  const int d = opt.dimension;
  BoxGeometry box;
  box.dim = d;
  for (int a = 0; a < d; ++a) box.max[a] = double(opt.n);
  const PointCloud cloud = make_lattice(box, 1.0);
  const double t0 = wall_seconds();
  const Families fam = radius_families(cloud, 3.015);
  LinearElastic mat;
  mat.E = 1.0;
  mat.nu = 0.25;
  mat.density = 1.0;
  mat.dim = d;
  mat.plane = d == 2 ? PlaneCondition::strain : PlaneCondition::none;
  CorrespondenceOptions copt;
  copt.stabilization = opt.stabilization;
  copt.stabilization_matrix_free = opt.matrix_free;
  CorrespondenceModel model(cloud, fam, mat, copt);
  const double setup = wall_seconds() - t0;

  std::vector<double> u(model.dofs()), f(model.dofs());
  for (std::size_t k = 0; k < u.size(); ++k) u[k] = 1e-3 * std::sin(0.37 * k);
  model.internal_force(u.data(), f.data());  // warm up
  int evals = 0;
  const double t1 = wall_seconds();
  while (evals < 3 || wall_seconds() - t1 < 2.0) {
    model.internal_force(u.data(), f.data());
    ++evals;
  }
  const double per_eval = (wall_seconds() - t1) / evals;
  const double bonds = double(fam.bonds());
  // Operator bytes streamed once per evaluation: G and G^T (index + d weights per bond),
  // plus S0 (index + value per entry) when assembled, or the matrix-free stabilization's two
  // bond passes (index + w V per bond each).
  const ScalarCsr* S0 = model.assembled_stabilization();
  const double s_bytes = S0 ? double(S0->nonzeros()) * (sizeof(ParticleId) + sizeof(double)) : 0.0;
  const double bytes = 2.0 * bonds * (sizeof(ParticleId) + d * sizeof(double)) +
                       (!model.stabilization() ? 0.0
                        : opt.matrix_free ? 2.0 * bonds * (sizeof(ParticleId) + sizeof(double))
                                          : s_bytes);
  const double gbs = bytes / per_eval / 1e9, stream = stream_triad_gbs();
  std::printf("particles                %zu\n", cloud.size());
  std::printf("bonds                    %.0f\n", bonds);
  std::printf("threads                  %d\n", omp_get_max_threads());
  std::printf("stabilization C_hg       %g (%s)\n", opt.stabilization, opt.matrix_free ? "matrix-free" : "assembled");
  std::printf("setup (search+assembly)  %.3f s\n", setup);
  std::printf("ms per evaluation        %.3f\n", per_eval * 1e3);
  std::printf("bond evaluations / s     %.3e\n", bonds / per_eval);
  std::printf("operator bytes / eval    %.3e\n", bytes);
  std::printf("achieved                 %.2f GB/s\n", gbs);
  std::printf("STREAM triad             %.2f GB/s (ratio %.2f)\n", stream, gbs / stream);
  std::printf("{\"particles\": %zu, \"bonds\": %.0f, \"threads\": %d, \"stabilization\": %g, \"matrix_free\": %s, "
              "\"seconds_per_evaluation\": %.6e, \"bond_evaluations_per_second\": %.6e, "
              "\"bytes_per_evaluation\": %.6e, \"achieved_gbs\": %.3f, \"stream_triad_gbs\": %.3f}\n",
              cloud.size(), bonds, omp_get_max_threads(), opt.stabilization, opt.matrix_free ? "true" : "false", per_eval,
              bonds / per_eval, bytes, gbs, stream);
  return 0;
}

}  // namespace perinom::cli

// perinom bench force on MPI ranks (issue 19): each rank owns a block of the Morton order,
// builds its families and operators on its local part (owned + ghosts within two horizons,
// neighbors/local_part.hpp), and an evaluation is one halo exchange of u followed by the
// local force on the owned and near rows (limit_rows); the owned rows are exact. --check gathers the force on rank 0 and compares it
// with the serial force, the global bond count with the serial one, and checks
// <G u, v> = <u, G^T v> over the ranks (v exchanged as a tensor field, as P would be).
// Partial: every rank builds the whole lattice's positions to choose its part.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench_model.hpp"
#include "commands.hpp"
#include "perinom/core/timer.hpp"
#include "perinom/distributed/ranks.hpp"
#include "perinom/neighbors/local_part.hpp"
#include "perinom/neighbors/partition.hpp"
#include "perinom/neighbors/search.hpp"

namespace perinom::cli {
namespace {

/// The tensor field of the adjoint check: cos(0.11 k) at component k of the cloud's d x d
/// fields.
double bench_tensor(std::size_t k) { return std::cos(0.11 * double(k)); }

/// Largest relative difference of the gathered force (curve order) from the serial one.
double serial_difference(const Options& opt, const PointCloud& cloud, const std::vector<ParticleId>& order,
                         const std::vector<double>& gathered, std::size_t& serial_bonds) {
  const int d = cloud.dim;
  const Families fam = radius_families(cloud, bench_horizon);
  serial_bonds = fam.bonds();
  CorrespondenceModel model(cloud, fam, bench_material(d), bench_options(opt));
  std::vector<double> u(model.dofs()), f(model.dofs());
  for (std::size_t k = 0; k < u.size(); ++k) u[k] = bench_displacement(k);
  model.internal_force(u.data(), f.data());
  double scale = 0.0, worst = 0.0;
  for (const double v : f) scale = std::max(scale, std::abs(v));
  for (std::size_t k = 0; k < order.size(); ++k)
    for (int a = 0; a < d; ++a)
      worst = std::max(worst, std::abs(gathered[k * d + a] - f[std::size_t(order[k]) * d + a]));
  return worst / scale;
}

}  // namespace

int bench_force_distributed(const Options& opt, const PointCloud& cloud) {
  const Ranks world = mpi_ranks();
  const int d = cloud.dim, d2 = d * d;
  const bool root = world.rank == 0;

  // 1. This rank's part, families and model.
  double t0 = wall_seconds();
  const std::vector<ParticleId> order = morton_order(cloud);
  const LocalPart part = local_part(cloud, order, world.size, world.rank, bench_horizon);
  const PointCloud local = subcloud(cloud, part.particles);
  const Families fam = radius_families(local, bench_horizon);
  CorrespondenceOptions copt = bench_options(opt);
  copt.fitted_rows = part.owned + part.near;  // the far ghosts' truncated families only lend values
  CorrespondenceModel model(local, fam, bench_material(d), copt);
  model.limit_rows(part.owned + part.near, part.owned);
  const double setup = max_over_ranks(wall_seconds() - t0);
  std::size_t owned_bonds = 0;
  for (std::size_t p = 0; p < part.owned; ++p) owned_bonds += std::size_t(fam.end(p) - fam.begin(p));

  // 2. u on the owned particles; the ghosts come from their owners.
  const std::vector<std::int64_t> ghosts(part.global.begin() + std::ptrdiff_t(part.owned), part.global.end());
  std::vector<double> u(model.dofs(), 0.0), f(model.dofs());
  for (std::size_t p = 0; p < part.owned; ++p)
    for (int a = 0; a < d; ++a) u[p * d + a] = bench_displacement(std::size_t(part.particles[p]) * d + a);
  Halo halo(part.owned, ghosts, d, u.data());
  halo.update();
  double exchange_error = 0.0;  // the ghosts' values against the field itself
  for (std::size_t p = part.owned; p < part.particles.size(); ++p)
    for (int a = 0; a < d; ++a)
      exchange_error = std::max(exchange_error, std::abs(u[p * d + a] - bench_displacement(std::size_t(part.particles[p]) * d + a)));
  exchange_error = max_over_ranks(exchange_error);

  // 3. Timing: the same number of evaluations on every rank
  auto evaluate = [&] {
    halo.update();
    model.internal_force(u.data(), f.data());
  };
  // (about 2 s, from three calls after a warm-up one, slowest rank; 0.2 s with --check).
  evaluate();
  barrier();
  t0 = wall_seconds();
  for (int c = 0; c < 3; ++c) evaluate();
  const double estimate = max_over_ranks(wall_seconds() - t0) / 3.0;
  // A check times only briefly: the CI runs it on more ranks than cores.
  const double window = opt.check ? 0.2 : 2.0;
  const long calls = std::max(3L, std::lround(window / std::max(estimate, 1e-9)));
  barrier();
  t0 = wall_seconds();
  for (long c = 0; c < calls; ++c) evaluate();
  const double per_eval = max_over_ranks((wall_seconds() - t0) / double(calls));
  barrier();
  t0 = wall_seconds();
  for (long c = 0; c < calls; ++c) halo.update();
  const double per_exchange = max_over_ranks((wall_seconds() - t0) / double(calls));

  // 4. The ranks' shares, for the report.
  const double owned = double(part.owned), ghost_share = double(part.ghosts()) / std::max(owned, 1.0);
  const double owned_max = max_over_ranks(owned), owned_min = -max_over_ranks(-owned);
  const double ghosts_max = max_over_ranks(ghost_share), ghosts_min = -max_over_ranks(-ghost_share);
  const double near_share = double(part.near) / std::max(owned, 1.0);
  const double near_max = max_over_ranks(near_share), near_min = -max_over_ranks(-near_share);
  const double bonds = sum_over_ranks(double(owned_bonds));

  // The ghosts must hold their owners' values whether or not the rest is checked.
  int failed = exchange_error != 0.0;
  if (failed && root) std::printf("check: ghost values %.3e from the field: the exchange FAILED\n", exchange_error);
  if (opt.check) {
    // <G u, v> = <u, G^T v> over the owned rows of all ranks, v exchanged as P would be.
    std::vector<double> H(model.particles() * d2), v(H.size(), 0.0), Gtv(model.dofs());
    model.G().apply(u.data(), d, H.data());
    for (std::size_t p = 0; p < part.owned; ++p)
      for (int k = 0; k < d2; ++k) v[p * d2 + k] = bench_tensor(std::size_t(part.particles[p]) * d2 + k);
    Halo tensors(part.owned, ghosts, d2, v.data());
    tensors.update();
    model.G().apply_transpose(v.data(), d, Gtv.data());
    double left = 0.0, right = 0.0;
    for (std::size_t p = 0; p < part.owned; ++p) {
      for (int k = 0; k < d2; ++k) left += H[p * d2 + k] * v[p * d2 + k];
      for (int a = 0; a < d; ++a) right += u[p * d + a] * Gtv[p * d + a];
    }
    left = sum_over_ranks(left), right = sum_over_ranks(right);
    const double adjoint = std::abs(left - right) / std::max(std::abs(left), 1e-300);
    // The force, gathered in curve order (the ranks' blocks follow each other).
    const std::vector<double> gathered = gather_on_root(std::vector<double>(f.begin(), f.begin() + std::ptrdiff_t(part.owned * d)));
    if (root) {
      std::size_t serial_bonds = 0;
      const double difference = serial_difference(opt, cloud, order, gathered, serial_bonds);
      std::printf("check: ghost values        %.3e from the field (exchange)\n", exchange_error);
      std::printf("check: bonds               %.0f on the ranks, %zu serial\n", bonds, serial_bonds);
      std::printf("check: force               %.3e relative to the serial force (tolerance 1e-12)\n", difference);
      std::printf("check: <G u, v> - <u, G^T v> %.3e relative (tolerance 1e-12)\n", adjoint);
      failed = failed || double(serial_bonds) != bonds || !(difference < 1e-12) || !(adjoint < 1e-12);
      std::printf("check: %s\n", failed ? "FAILED" : "passed");
    }
    failed = int(max_over_ranks(double(failed)));
  }
  if (root) {
    std::printf("ranks                    %d (%d threads each)\n", world.size, omp_get_max_threads());
    std::printf("particles                %zu\n", cloud.size());
    std::printf("bonds                    %.0f (%.1f per particle)\n", bonds, bonds / double(cloud.size()));
    std::printf("owned per rank           %.0f-%.0f; ghosts %.0f%%-%.0f%% of owned (near ones, whose rows are "
                "evaluated: %.0f%%-%.0f%%)\n", owned_min, owned_max, 100.0 * ghosts_min, 100.0 * ghosts_max,
                100.0 * near_min, 100.0 * near_max);
    std::printf("setup (part+search+assembly) %.3f s (slowest rank)\n", setup);
    std::printf("ms per evaluation        %.3f (exchange of u and the local force; slowest rank)\n", per_eval * 1e3);
    std::printf("  exchange of u alone    %.3f ms\n", per_exchange * 1e3);
    std::printf("{\"ranks\": %d, \"threads\": %d, \"particles\": %zu, \"bonds\": %.0f, \"ghosts_max\": %.4f, "
                "\"setup_seconds\": %.6e, \"seconds_per_evaluation\": %.6e, \"seconds_per_exchange\": %.6e, "
                "\"check\": %s}\n",
                world.size, omp_get_max_threads(), cloud.size(), bonds, ghosts_max, setup, per_eval, per_exchange,
                !opt.check ? "null" : failed ? "\"failed\"" : "\"passed\"");
  }
  return failed ? 1 : 0;
}

}  // namespace perinom::cli

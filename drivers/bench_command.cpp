// perinom bench force: times the explicit force evaluation (G product, pointwise law,
// transposed product, and the stabilization product) on an n^d simple-cubic lattice with
// horizon ratio 3.015, measures this machine's STREAM-triad bandwidth, and ends with one
// JSON object on the last line. Under mpirun, or with --check, the distributed force
// (bench_distributed.cpp).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "bench_model.hpp"
#include "commands.hpp"
#include "perinom/distributed/ranks.hpp"
#include "perinom/core/error.hpp"
#include "perinom/core/thread_governor.hpp"
#include "perinom/core/timer.hpp"
#include "perinom/geometry/lattice.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/neighbors/bond_graph.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
#include "perinom/operators/stabilization_term.hpp"
#include "perinom/operators/scalar_csr.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/verlet.hpp"

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

/// Calls f under a governor until its first trial has chosen the thread count, which the
/// governed loops started in the next 10 trial lengths keep: the timings that follow measure
/// the choice, not the trial (whose iterations on one thread made a 2 s window of 300 ms
/// evaluations mostly single-threaded).
template <class F>
void settle_governor(F&& f) {
  ThreadGovernor governor;
  while (governor.active() && governor.trials() < 1) {
    governor.tick();
    f();
  }
}

/// Seconds per call of f: after a warm-up call and the governor's trial, at least 3 calls and
/// 2 s. The calls are governed as a solver's iterations are (core/thread_governor.hpp;
/// PERINOM_THREAD_GOVERNOR=off times the fixed team).
template <class F>
double seconds_per_call(F&& f) {
  f();
  settle_governor(f);
  int calls = 0;
  ThreadGovernor governor;
  const double t0 = wall_seconds();
  while (calls < 3 || wall_seconds() - t0 < 2.0) {
    governor.tick();
    f();
    ++calls;
  }
  return (wall_seconds() - t0) / calls;
}

/// Seconds per iteration of an explicit solver on the lattice with its bottom layer fixed and
/// a downward force on its top layer: `solve(loading, observer)` runs first + k iterations,
/// timed between the observer's calls at iterations `first` and first + k (the stiffness row
/// sums every explicit solver computes before its loop are not counted).
template <class Solve>
double seconds_per_iteration(CorrespondenceModel& model, const PointCloud& cloud, long n,
                             std::int64_t first, std::int64_t k, Solve&& solve) {
  const int d = cloud.dim;
  Loading loading;
  loading.force.assign(model.dofs(), 0.0);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double h = cloud.x[i * d + d - 1];
    if (h < 1.0)
      for (int a = 0; a < d; ++a) loading.fix(static_cast<std::int64_t>(i * d + a), 0.0);
    if (h > double(n) - 1.0) loading.force[i * d + d - 1] = -1e-3;
  }
  // The solver's governor keeps the choice of a trial run just before (settle_governor).
  std::vector<double> u0(model.dofs(), 0.0), f0(model.dofs());
  settle_governor([&] { model.internal_force(u0.data(), f0.data()); });
  double t_first = 0.0, t_last = 0.0;
  std::int64_t timed = 0;  // the iterations after `first` the solve did (ADR can converge at
                           // its rounding floor before first + k: the time was negative)
  Observer timing;
  timing.every = 1;
  timing.call = [&](std::int64_t it, double, const std::vector<double>&) {
    if (it == first) t_first = wall_seconds();
    else if (it > first && it <= first + k) t_last = wall_seconds(), timed = it - first;
  };
  solve(loading, timing);
  return timed > 0 ? (t_last - t_first) / double(timed) : NAN;
}

/// A time for the JSON line: %.6e, or null when it was not measured (NaN).
std::string json_seconds(double t) {
  if (!std::isfinite(t)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.6e", t);
  return text;
}

/// perinom bench refresh: breaks B random bonds (fixed seed) of the lattice's radius
/// families and times the refresh of the rows they touch (G, G^T, the matrix-free and the
/// fused stabilization) against a full build of the same operators from the bond weights.
/// Ends with one JSON object on the last line.
int bench_refresh(const Options& opt, const PointCloud& cloud) {
  const int d = cloud.dim;
  // 1. The families and what a model assembles from them (radius families: fused S applies).
  const Families fam = radius_families(cloud, bench_horizon);
  auto graph = std::make_shared<BondGraph>(fam);
  const double modulus = 0.5 * 2.0 * 1.0;  // C_hg 2 mu
  auto build = [&] {
    const BondWeights bw = bond_weights(cloud, fam, Influence::inverse_square);
    auto G = std::make_unique<NonlocalOperator>(cloud, graph, bw);
    auto S = make_stabilization(cloud, *G, modulus, AssemblyLevel::fused);
    return std::make_pair(std::move(G), std::move(S));
  };
  // 2. A full build, timed (best of three).
  double build_seconds = 1e300;
  for (int rep = 0; rep < 3; ++rep) {
    const double t0 = wall_seconds();
    build();
    build_seconds = std::min(build_seconds, wall_seconds() - t0);
  }
  auto [G, S] = build();
  // 3. B distinct random bonds, broken in both directions.
  std::mt19937_64 rng(2026);
  std::vector<std::pair<ParticleId, ParticleId>> breaks;
  std::set<std::pair<ParticleId, ParticleId>> chosen;
  const long wanted = std::min<long>(opt.bonds, static_cast<long>(fam.bonds() / 4));
  while (static_cast<long>(breaks.size()) < wanted) {
    const std::size_t i = rng() % fam.particles();
    const ParticleId j = fam.neighbors[fam.begin(i) + static_cast<Offset>(rng() % (fam.end(i) - fam.begin(i)))];
    if (chosen.insert({std::min<ParticleId>(i, j), std::max<ParticleId>(i, j)}).second)
      breaks.emplace_back(static_cast<ParticleId>(i), j);
  }
  const std::vector<ParticleId> rows = graph->rows_touched(breaks);
  for (const auto& [i, j] : breaks) graph->break_bond(i, j);
  // 4. The refresh of the touched rows, timed as the build is (best of several calls, the
  //    fixed team; it is idempotent, so it can be repeated).
  double refresh_seconds = 1e300, spent = 0.0;
  for (int rep = 0; rep < 3 || (rep < 1000 && spent < 1.0); ++rep) {
    const double t0 = wall_seconds();
    G->refresh_rows(rows);
    S->refresh_rows(rows);
    const double t = wall_seconds() - t0;
    refresh_seconds = std::min(refresh_seconds, t);
    spent += t;
  }
  std::printf("particles                %zu\n", cloud.size());
  std::printf("bonds                    %zu (%.1f per particle)\n", fam.bonds(), double(fam.bonds()) / cloud.size());
  std::printf("threads                  %d\n", omp_get_max_threads());
  std::printf("bonds broken             %zu (%zu rows refreshed, %zu detached)\n", breaks.size(), rows.size(),
              G->detached().size());
  std::printf("full build (G, S, fused) %.3f s\n", build_seconds);
  std::printf("refresh                  %.3e s (%.3f%% of a full build)\n", refresh_seconds,
              100.0 * refresh_seconds / build_seconds);
  std::printf("{\"dimension\": %d, \"particles\": %zu, \"bonds\": %zu, \"threads\": %d, \"bonds_broken\": %zu, "
              "\"rows_refreshed\": %zu, \"refresh_seconds\": %.6e, \"build_seconds\": %.6e, \"ratio\": %.6e}\n",
              d, cloud.size(), fam.bonds(), omp_get_max_threads(), breaks.size(), rows.size(), refresh_seconds,
              build_seconds, refresh_seconds / build_seconds);
  return 0;
}

}  // namespace

int bench(const Options& opt) {
  if (opt.positional.size() != 1 || (opt.positional[0] != "force" && opt.positional[0] != "refresh"))
    throw InputError("bench: the benchmarks are 'force' and 'refresh'");
  if (opt.dimension != 2 && opt.dimension != 3) throw InputError("--dimension must be 2 or 3");
  if (opt.n < 4) throw InputError("--n must be at least 4");
  const int d = opt.dimension;
  if (std::pow(double(opt.n), d) > 2.0e9)
    throw InputError("--n: " + std::to_string(opt.n) + "^" + std::to_string(d) +
                     " particles are more than perinom's limit of 2e9");
  BoxGeometry box;
  box.dim = d;
  for (int a = 0; a < d; ++a) box.max[a] = double(opt.n);
  const PointCloud cloud = make_lattice(box, 1.0);
  if (opt.positional[0] == "refresh") return bench_refresh(opt, cloud);
  if (mpirun_processes() > 1 || opt.check) return bench_force_distributed(opt, cloud);
  const double t0 = wall_seconds();
  const Families fam = radius_families(cloud, bench_horizon);
  CorrespondenceModel model(cloud, fam, bench_material(d), bench_options(opt));
  const double setup = wall_seconds() - t0;

  std::vector<double> u(model.dofs()), f(model.dofs());
  for (std::size_t k = 0; k < u.size(); ++k) u[k] = bench_displacement(k);
  const double per_eval = seconds_per_call([&] { model.internal_force(u.data(), f.data()); });
  // The two products alone, for the roofline (H and Q are the model's own sizes).
  std::vector<double> H(model.particles() * d * d), Q(H.size(), 1.0);
  const double per_grad = seconds_per_call([&] { model.G().apply(u.data(), d, H.data()); });
  const double per_transpose = seconds_per_call([&] { model.G().apply_transpose(Q.data(), d, f.data()); });
  // One ADR iteration and one Velocity Verlet step, each over about 2 s.
  const std::int64_t first = 5, k = std::max<std::int64_t>(5, std::llround(2.0 / per_eval));
  const double adr_iteration = seconds_per_iteration(model, cloud, opt.n, first, k, [&](const Loading& l, const Observer& o) {
    AdrOptions a;
    a.tolerance = 0.0;  // never converged: exactly first + k iterations
    a.max_iterations = first + k;
    std::vector<double> x;
    solve_adr(model, l, a, x, nullptr, o);
  });
  const double verlet_step = seconds_per_iteration(model, cloud, opt.n, first, k, [&](const Loading& l, const Observer& o) {
    VerletOptions v;
    v.steps = first + k;
    v.history_every = first + k + 1;  // energies at the start only, outside the timed steps
    std::vector<double> x, y;
    solve_verlet(model, l, v, x, y, nullptr, o);
  });

  const double bonds = double(fam.bonds());
  // Operator bytes streamed once per evaluation: G and G^T (index + d weights per bond),
  // plus, for S: one more weight per bond in G's pass (fused), S0 (index + value per entry;
  // assembled), or the matrix-free stabilization's two bond passes (index + w V per bond each).
  const double w_bytes = opt.single_precision ? sizeof(float) : sizeof(double);
  const double product_bytes = bonds * (sizeof(ParticleId) + d * w_bytes);
  const StabilizationTerm* S = model.stabilization();
  const AssemblyLevel level = S ? S->level() : AssemblyLevel::assembled;
  const double s_bytes = !S                                 ? 0.0
                         : level == AssemblyLevel::fused     ? bonds * w_bytes
                         : level == AssemblyLevel::assembled ? double(S->stored()->nonzeros()) * (sizeof(ParticleId) + sizeof(double))
                                                             : 2.0 * bonds * (sizeof(ParticleId) + sizeof(double));
  const char* storage = !S                                 ? "none"
                        : level == AssemblyLevel::fused     ? "fused"
                        : level == AssemblyLevel::assembled ? "assembled"
                                                            : "matrix_free";
  const double bytes = 2.0 * product_bytes + s_bytes;
  const double gbs = bytes / per_eval / 1e9, stream = stream_triad_gbs();
  std::printf("particles                %zu\n", cloud.size());
  std::printf("bonds                    %.0f (%.1f per particle)\n", bonds, bonds / cloud.size());
  std::printf("threads                  %d\n", omp_get_max_threads());
  std::printf("weights                  %s\n", opt.single_precision ? "single precision (float)" : "double precision");
  std::printf("stabilization C_hg       %g (%s)\n", opt.stabilization, storage);
  std::printf("setup (search+assembly)  %.3f s\n", setup);
  std::printf("ms per evaluation        %.3f\n", per_eval * 1e3);
  std::printf("  gradient product G u   %.3f ms (%.2f GB/s)\n", per_grad * 1e3, product_bytes / per_grad / 1e9);
  std::printf("  transposed G^T q       %.3f ms (%.2f GB/s)\n", per_transpose * 1e3, product_bytes / per_transpose / 1e9);
  if (std::isfinite(adr_iteration)) std::printf("ms per ADR iteration     %.3f\n", adr_iteration * 1e3);
  else std::printf("ms per ADR iteration     n/a (ADR converged before iteration %lld: a larger --n)\n", (long long)first + 1);
  std::printf("ms per Verlet step       %.3f\n", verlet_step * 1e3);
  std::printf("bond evaluations / s     %.3e\n", bonds / per_eval);
  std::printf("operator bytes / eval    %.3e (%.1f per bond)\n", bytes, bytes / bonds);
  std::printf("achieved                 %.2f GB/s\n", gbs);
  std::printf("STREAM triad             %.2f GB/s (ratio %.2f); bound %.3e bond evaluations / s\n", stream,
              gbs / stream, stream * 1e9 / (bytes / bonds));
  std::printf("{\"particles\": %zu, \"bonds\": %.0f, \"threads\": %d, \"stabilization\": %g, \"storage\": \"%s\", "
              "\"single_precision\": %s, \"seconds_per_evaluation\": %.6e, \"seconds_per_adr_iteration\": %s, \"seconds_per_verlet_step\": %.6e, "
              "\"bond_evaluations_per_second\": %.6e, \"bytes_per_evaluation\": %.6e, \"achieved_gbs\": %.3f, "
              "\"stream_triad_gbs\": %.3f}\n",
              cloud.size(), bonds, omp_get_max_threads(), opt.stabilization, storage,
              opt.single_precision ? "true" : "false", per_eval, json_seconds(adr_iteration).c_str(), verlet_step, bonds / per_eval, bytes, gbs, stream);
  return 0;
}

}  // namespace perinom::cli

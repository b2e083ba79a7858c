// The row screen (lib/fracture/row_screen.hpp) keeps every row that holds a bond at the
// threshold, so a criterion that reads only those rows breaks the bonds a full pass breaks; and
// it keeps few rows when little has moved since its snapshot (else it would save nothing).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "../../lib/fracture/row_screen.hpp"
#include "../support/clouds.hpp"
#include "perinom/fracture/bond_breaking.hpp"
#include "perinom/fracture/bond_measures.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/scene.hpp"

using namespace perinom;

namespace {

// Each row's largest measure over its live bonds.
template <class Measure>
std::vector<double> row_maxima(const BondGraph& g, const Measure& m) {
  std::vector<double> top(g.rows(), 0.0);
  for (std::size_t i = 0; i < g.rows(); ++i) g.for_each_live(i, [&](Offset, ParticleId j) { top[i] = std::max(top[i], m(i, j)); });
  return top;
}

// A smooth field plus noise of relative size `noise` (N x c).
std::vector<double> field(const PointCloud& c, int comps, double scale, double noise, std::uint64_t seed) {
  std::vector<double> v = test::random_field(c.size() * comps, scale * noise, seed);
  for (std::size_t i = 0; i < c.size(); ++i)
    for (int a = 0; a < comps; ++a) v[i * comps + a] += scale * std::sin(0.3 * c.x[i * c.dim] + 0.2 * a + 0.1 * c.x[i * c.dim + c.dim - 1]);
  return v;
}

}  // namespace

TEST_CASE("the row screen keeps every row with a bond at the threshold, and few after a small change", "[fracture]") {
  for (const int d : {2, 3}) {
    for (const bool knn : {false, true}) {
      INFO("dim " << d << (knn ? ", nearest neighbours" : ", radius"));
      const PointCloud c = test::lattice(d, d == 2 ? 40 : 12, 0.3);
      BondGraph g(knn ? knn_families(c, d == 2 ? 33 : 60) : radius_families(c, 3.015));
      const std::size_t n = c.size();
      const auto u0 = field(c, d, 1e-2, 0.5, 5);
      const auto H0 = field(c, d * d, 1e-2, 0.5, 6);
      for (const bool with_H : {true, false}) {
        INFO((with_H ? "hourglass strain" : "stretch ratio"));
        auto measure = [&](const double* u, const double* H) {
          return [&, u, H](std::size_t i, std::size_t j) {
            return H ? HourglassStrain{d, c.x.data(), u, H}(i, j)
                     : std::sqrt(BondStretch{d, c.x.data(), u}.squared_ratio(i, j));
          };
        };
        detail::RowScreen screen(c, g);
        screen.take(u0.data(), with_H ? H0.data() : nullptr, row_maxima(g, measure(u0.data(), with_H ? H0.data() : nullptr)));
        // Bonds die between the snapshot and the check: the bound holds over the survivors.
        for (std::size_t i = 0; i < n; i += 7) g.break_bond(static_cast<ParticleId>(i), g.col(g.begin(i)));
        for (const double step : {1e-4, 1e-3, 1e-2}) {
          std::vector<double> u = u0, H = H0;
          const auto du = field(c, d, step, 2.0, 11), dH = field(c, d * d, step, 2.0, 12);
          for (std::size_t k = 0; k < u.size(); ++k) u[k] += du[k];
          for (std::size_t k = 0; k < H.size(); ++k) H[k] += dH[k];
          const auto now = row_maxima(g, measure(u.data(), with_H ? H.data() : nullptr));
          std::vector<double> sorted = now;
          std::sort(sorted.begin(), sorted.end());
          for (const double q : {0.5, 0.9, 0.99, 1.0}) {
            const double t = sorted[static_cast<std::size_t>(q * (n - 1))];
            const auto rows = screen.rows_reaching(u.data(), with_H ? H.data() : nullptr, t);
            REQUIRE(std::is_sorted(rows.begin(), rows.end()));
            std::size_t missed = 0;
            for (std::size_t i = 0; i < n; ++i)
              if (now[i] >= t && !std::binary_search(rows.begin(), rows.end(), static_cast<ParticleId>(i))) ++missed;
            CHECK(missed == 0);
            // A small change keeps few rows: at the 90% quantile, under a fifth of them.
            if (step == 1e-4 && q == 0.9) CHECK(rows.size() < n / 5);
          }
        }
      }
    }
  }
}

TEST_CASE("screened criteria break the bonds a pass over every row breaks, step by step", "[fracture][sent]") {
  // Two copies of the coarse SENT plate pulled by a growing field with local noise: one reads
  // only the rows its screen keeps, the other every row. The bonds found, and so the models,
  // stay the same through arming, breaks, refreshed rows and new snapshots; and through a
  // jolt (steps 301-320: a new random field each step, so snapshots stop paying and the screen
  // reads every row for a while) and the calm after it. Small steps, so that the screen
  // keeps few rows between snapshots.
  const Scene scene = read_scene(std::string(PERINOM_SOURCE_DIR) + "/examples/sent.yaml");
  for (const DamageCriterion criterion : {DamageCriterion::instability, DamageCriterion::stretch}) {
    INFO((criterion == DamageCriterion::instability ? "instability" : "stretch"));
    Problem a = build_problem(scene), b = build_problem(scene);
    const double parameter = 0.02;
    BondBreaking screened(a.as<CorrespondenceModel>(), a.cloud, criterion, parameter);
    BondBreaking every(b.as<CorrespondenceModel>(), b.cloud, criterion, parameter);
    every.screen(false);
    const std::size_t n = a.cloud.size();
    const auto noise = test::random_field(n * 2, 1.0, 9);
    std::vector<double> u(n * 2);
    std::size_t found = 0;
    for (int step = 1; step <= 600; ++step) {
      const double e = 8e-5 * step;  // mean strain
      const bool jolt = step > 300 && step <= 320;
      const auto shake = test::random_field(n * 2, jolt ? 0.25 * e * 5e-5 : 0.0, 100 + step);
      for (std::size_t i = 0; i < n; ++i) {
        const double x = a.cloud.x[2 * i], y = a.cloud.x[2 * i + 1];
        u[2 * i] = -0.3 * e * x + 2e-3 * e * 5e-5 * noise[2 * i] + shake[2 * i];
        u[2 * i + 1] = e * y + 0.3 * e * 5e-5 * noise[2 * i + 1] * std::exp(-std::abs(y - 5e-4) / 5e-5) + shake[2 * i + 1];
      }
      INFO("step " << step);
      REQUIRE(screened.find(u.data()) == every.find(u.data()));
      REQUIRE(screened.due() == every.due());
      found += screened.due().size();
      screened.apply();
      every.apply();
    }
    INFO(found << " bonds found");
    CHECK(found > 50);
    CHECK(screened.broken() == every.broken());
  }
}

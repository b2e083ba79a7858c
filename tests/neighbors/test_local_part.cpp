// A rank's local part (owned block + ghosts within 2 delta) carries everything its owned rows
// read: a model built on the local cloud alone, evaluating only its owned and near rows
// (limit_rows), gives the serial force on the owned ones. This is the distributed force
// without the exchange (the MPI tests add it).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include "../support/clouds.hpp"
#include "../support/refresh.hpp"
#include "perinom/geometry/lattice.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/neighbors/local_part.hpp"
#include "perinom/neighbors/partition.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

namespace {

constexpr double horizon = 3.015;

/// The local parts' owned rows of the force, each rank's model built on its own cloud
/// (evaluating all its rows, or only the owned and near ones), against the serial force
/// (relative to its largest entry); also the owned rows' bonds and the ghosts' grouping.
void check_parts(const PointCloud& cloud, const CorrespondenceOptions& options, int ranks, bool limited) {
  const int d = cloud.dim;
  const Families whole = radius_families(cloud, horizon);
  CorrespondenceModel serial(cloud, whole, test::elastic_material(d), options);
  const std::vector<double> u = test::random_field(serial.dofs(), 1e-3, 11);
  std::vector<double> f(serial.dofs());
  serial.internal_force(u.data(), f.data());
  const double scale = test::max_abs(f);

  const std::vector<ParticleId> order = morton_order(cloud);
  std::set<ParticleId> seen;
  std::size_t bonds = 0;
  double worst = 0.0;
  for (int r = 0; r < ranks; ++r) {
    const LocalPart part = local_part(cloud, order, ranks, r, horizon);
    const PointCloud local = subcloud(cloud, part.particles);
    const Families fam = radius_families(local, horizon);
    CorrespondenceModel model(local, fam, test::elastic_material(d), options);
    if (limited) model.limit_rows(part.owned + part.near, part.owned);
    std::vector<double> ul(model.dofs()), fl(model.dofs(), 1.0);
    for (std::size_t p = 0; p < part.particles.size(); ++p)
      for (int a = 0; a < d; ++a) ul[p * d + a] = u[part.particles[p] * d + a];
    model.internal_force(ul.data(), fl.data());
    for (std::size_t p = 0; p < part.owned; ++p) {
      const ParticleId i = part.particles[p];
      REQUIRE(seen.insert(i).second);  // owned once
      REQUIRE(part.global[p] == static_cast<std::int64_t>(part.first + p));
      bonds += static_cast<std::size_t>(fam.end(p) - fam.begin(p));
      CHECK(fam.end(p) - fam.begin(p) == whole.end(i) - whole.begin(i));
      for (int a = 0; a < d; ++a) worst = std::max(worst, std::abs(fl[p * d + a] - f[i * d + a]) / scale);
    }
    if (limited)  // the rows not written are zero
      CHECK(std::all_of(fl.begin() + std::ptrdiff_t(part.owned * d), fl.end(), [](double v) { return v == 0.0; }));
    for (std::size_t p = part.owned; p < part.particles.size(); ++p) {
      const ParticleId i = part.particles[p];
      double nearest = 1e300;  // to an owned particle
      for (std::size_t q = 0; q < part.owned; ++q) {
        double r2 = 0.0;
        for (int a = 0; a < d; ++a) r2 += std::pow(cloud.x[i * d + a] - cloud.x[part.particles[q] * d + a], 2);
        nearest = std::min(nearest, std::sqrt(r2));
      }
      CHECK(nearest <= 2.0 * horizon * (1.0 + 1e-9));
      CHECK((p < part.owned + part.near) == (nearest <= horizon * (1.0 + 1e-9)));
      if (p > part.owned && p != part.owned + part.near)
        CHECK(part.global[p] > part.global[p - 1]);  // each group in curve order, none owned
      CHECK((part.global[p] < static_cast<std::int64_t>(part.first) ||
             part.global[p] >= static_cast<std::int64_t>(part.first + part.owned)));
      CHECK(order[part.global[p]] == part.particles[p]);
    }
  }
  CHECK(seen.size() == cloud.size());
  CHECK(bonds == whole.bonds());
  CHECK(worst < 1e-12);
}

}  // namespace

TEST_CASE("a model on a rank's local part gives the serial force on its owned rows", "[neighbors][partition]") {
  for (const int dim : {2, 3}) {
    const PointCloud cloud = dim == 2 ? test::lattice(2, 23, 0.2, 5) : test::lattice(3, 11, 0.2, 6);
    for (const char* storage : {"fused", "assembled", "matrix_free"}) {
      CorrespondenceOptions o{Influence::inverse_square, 0.5, Formulation::classical};
      REQUIRE(parse_stabilization_storage(storage, o.stabilization_storage));
      for (const int ranks : {1, 2, 3, 5})
        for (const bool limited : {false, true}) {
          INFO("dimension " << dim << ", " << storage << ", " << ranks << " ranks, limited " << limited);
          check_parts(cloud, o, ranks, limited);
        }
    }
  }
}

TEST_CASE("the local parts stay exact around a hole and on a slender strip", "[neighbors][partition]") {
  // Where a part is weakest: families cut by a hole (a rank's block borders it), and a strip
  // 40 x 4 cut by the curve into short blocks whose ghosts outnumber their owned particles.
  const CorrespondenceOptions o{Influence::inverse_square, 0.5, Formulation::classical};
  PointCloud holed = test::lattice(2, 24, 0.2, 9), kept;
  kept.dim = 2, kept.dx = holed.dx, kept.spacing = holed.spacing;
  for (std::size_t i = 0; i < holed.size(); ++i) {
    const double* p = holed.point(i);
    if (std::hypot(p[0] - 12.0, p[1] - 12.0) < 5.0) continue;
    kept.x.insert(kept.x.end(), p, p + 2);
    kept.volume.push_back(holed.volume[i]);
  }
  BoxGeometry strip;
  strip.dim = 2, strip.max[0] = 40.0, strip.max[1] = 4.0;
  const PointCloud slender = make_lattice(strip, 1.0, 0.1, 3);
  for (const PointCloud* cloud : {static_cast<const PointCloud*>(&kept), &slender})
    for (const int ranks : {2, 3, 7}) {
      INFO((cloud == &kept ? "hole, " : "strip, ") << ranks << " ranks");
      check_parts(*cloud, o, ranks, true);
    }
}

TEST_CASE("without the far ghosts the near rows, and so the owned force, are wrong", "[neighbors][partition]") {
  // The far ghosts (one to two horizons out) lend only their u, but the near rows' G u reads
  // it: a part cut at one horizon gives a wrong owned force.
  const PointCloud cloud = test::lattice(2, 23, 0.2, 5);
  const CorrespondenceOptions o{Influence::inverse_square, 0.5, Formulation::classical};
  CorrespondenceModel serial(cloud, radius_families(cloud, horizon), test::elastic_material(2), o);
  const std::vector<double> u = test::random_field(serial.dofs(), 1e-3, 11);
  std::vector<double> f(serial.dofs());
  serial.internal_force(u.data(), f.data());
  const LocalPart part = local_part(cloud, morton_order(cloud), 2, 0, horizon);
  REQUIRE(part.ghosts() > part.near);
  const std::vector<ParticleId> cut(part.particles.begin(), part.particles.begin() + std::ptrdiff_t(part.owned + part.near));
  const PointCloud local = subcloud(cloud, cut);
  CorrespondenceModel model(local, radius_families(local, horizon), test::elastic_material(2), o);
  model.limit_rows(cut.size(), part.owned);
  std::vector<double> ul(model.dofs()), fl(model.dofs());
  for (std::size_t p = 0; p < cut.size(); ++p)
    for (int a = 0; a < 2; ++a) ul[p * 2 + a] = u[cut[p] * 2 + a];
  model.internal_force(ul.data(), fl.data());
  double worst = 0.0;
  for (std::size_t p = 0; p < part.owned; ++p)
    for (int a = 0; a < 2; ++a) worst = std::max(worst, std::abs(fl[p * 2 + a] - f[cut[p] * 2 + a]));
  CHECK(worst > 1e-6 * test::max_abs(f));
}

TEST_CASE("limit_rows is refused for formulations whose rows read the whole body", "[neighbors][partition]") {
  const PointCloud cloud = test::lattice(2, 9, 0.0, 5);
  const Families f = radius_families(cloud, horizon);
  CorrespondenceModel model(cloud, f, test::elastic_material(2), {Influence::inverse_square, 0.5, Formulation::classical});
  CHECK_THROWS_AS(model.limit_rows(10, 20), std::logic_error);
  CHECK_THROWS_AS(model.limit_rows(cloud.size() + 1, 1), std::logic_error);
}

TEST_CASE("k-nearest families restricted to a part keep the owned and near families whole", "[neighbors][partition]") {
  // A regular lattice: ties at the k-th distance everywhere, so the families are searched on
  // the whole cloud and restricted (local_families), the part cut at the largest support.
  for (const int dim : {2, 3}) {
    const PointCloud cloud = dim == 2 ? test::lattice(2, 19, 0.0, 1) : test::lattice(3, 9, 0.0, 1);
    const Families whole = knn_families(cloud, dim == 2 ? 12 : 26);
    const double reach = *std::max_element(whole.support.begin(), whole.support.end());
    CorrespondenceOptions o{Influence::inverse_square, 0.5, Formulation::classical};
    CorrespondenceModel serial(cloud, whole, test::elastic_material(dim), o);
    const std::vector<double> u = test::random_field(serial.dofs(), 1e-3, 3);
    std::vector<double> f(serial.dofs());
    serial.internal_force(u.data(), f.data());
    const double scale = test::max_abs(f);
    for (const int ranks : {2, 3}) {
      for (int r = 0; r < ranks; ++r) {
        INFO("dimension " << dim << ", rank " << r << " of " << ranks);
        const LocalPart part = local_part(cloud, morton_order(cloud), ranks, r, reach);
        const Families fam = local_families(whole, part);
        REQUIRE(fam.particles() == part.particles.size());
        for (std::size_t p = 0; p < part.owned + part.near; ++p) {
          const ParticleId i = part.particles[p];
          std::set<ParticleId> mine, expected(whole.neighbors.begin() + whole.begin(i), whole.neighbors.begin() + whole.end(i));
          for (Offset k = fam.begin(p); k < fam.end(p); ++k) mine.insert(part.particles[fam.neighbors[k]]);
          CHECK(mine == expected);
          CHECK(fam.support[p] == whole.support[i]);
        }
        const PointCloud local = subcloud(cloud, part.particles);
        CorrespondenceModel model(local, fam, test::elastic_material(dim), o);
        model.limit_rows(part.owned + part.near, part.owned);
        std::vector<double> ul(model.dofs()), fl(model.dofs());
        for (std::size_t p = 0; p < part.particles.size(); ++p)
          for (int a = 0; a < dim; ++a) ul[p * dim + a] = u[part.particles[p] * dim + a];
        model.internal_force(ul.data(), fl.data());
        double worst = 0.0;
        for (std::size_t p = 0; p < part.owned; ++p)
          for (int a = 0; a < dim; ++a)
            worst = std::max(worst, std::abs(fl[p * dim + a] - f[part.particles[p] * dim + a]) / scale);
        CHECK(worst < 1e-12);
      }
    }
  }
}

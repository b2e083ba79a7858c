// A distributed rank's thin plate (issue 19): the plate of a local part's nodes and their
// mirrors, fitted at the owned and near nodes, gives the whole plate's force, stiffness rows
// and energy share on the owned nodes. This is the distributed plate without the exchange
// (the MPI tests add it).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include "../support/clouds.hpp"
#include "perinom/models/thin_plate.hpp"
#include "perinom/neighbors/local_part.hpp"
#include "perinom/neighbors/partition.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

namespace {

constexpr EdgeSupport ss = EdgeSupport::simply_supported, cl = EdgeSupport::clamped, fr = EdgeSupport::free;

ThinPlateOptions steel() {
  ThinPlateOptions o;
  o.E = 210e9, o.nu = 0.3, o.thickness = 0.01, o.density = 7800.0, o.stabilization = 0.5;
  return o;
}

/// The physical nodes of a plate as a cloud (what the ranks partition).
PointCloud nodes_of(const PlateCloud& plate) {
  PointCloud c;
  c.dim = 2;
  c.dx = plate.cloud.dx;
  c.spacing = plate.cloud.spacing;
  c.x.assign(plate.cloud.x.begin(), plate.cloud.x.begin() + std::ptrdiff_t(2 * plate.physical));
  c.volume = plate.area;
  return c;
}

}  // namespace

TEST_CASE("a rank's plate gives the whole plate's force, stiffness rows and energy on its owned nodes",
          "[models][plate][partition]") {
  const double ratio = 3.015, dx = 1.0 / 12;
  BoxGeometry box;
  box.dim = 2;
  box.max = {1.0, 0.75, 0.0};
  box.thickness = 0.01;
  for (const PlateEdges edges : {PlateEdges{ss, ss, ss, ss}, PlateEdges{cl, cl, cl, cl}, PlateEdges{fr, cl, ss, fr}}) {
    PlateCloud whole = make_plate_cloud(box, dx, edges, 3);
    const PointCloud nodes = nodes_of(whole);
    ThinPlateModel serial(whole, radius_families(whole.cloud, ratio * dx), steel());
    const std::vector<double> w = test::random_field(serial.dofs(), 1e-3, 5);
    std::vector<double> f(serial.dofs());
    serial.internal_force(w.data(), f.data());
    const double scale = test::max_abs(f);
    std::vector<std::vector<ParticleId>> cols(serial.dofs());
    std::vector<std::vector<double>> vals(serial.dofs());
    serial.visit_tangent_rows([&](std::size_t r, const std::vector<ParticleId>& c, const std::vector<double>& v) {
      cols[r] = c, vals[r] = v;
    });
    const std::vector<double> sums = serial.stiffness_row_sums();
    const double W = serial.energy(w.data());

    for (const int ranks : {2, 3}) {
      const std::vector<ParticleId> order = morton_order(nodes);
      std::set<ParticleId> seen;
      double worst = 0.0, worst_k = 0.0, shares = 0.0;
      for (int rank = 0; rank < ranks; ++rank) {
        const LocalPart part = local_part(nodes, order, ranks, rank, ratio * dx);
        PlateCloud mine = sub_plate(whole, part.particles);
        REQUIRE(mine.physical == part.particles.size());
        for (std::size_t g = 0; g < mine.image.size(); ++g)  // each mirror's image is a local node
          REQUIRE(static_cast<std::size_t>(mine.image[g]) < mine.physical);
        const Families fam = radius_families(mine.cloud, ratio * dx);
        ThinPlateOptions o = steel();
        o.fitted_rows = part.owned + part.near;  // the far nodes' truncated families are not fitted
        ThinPlateModel local(std::move(mine), fam, o);
        local.limit_rows(part.owned + part.near, part.owned);
        std::vector<double> wl(local.dofs()), fl(local.dofs());
        for (std::size_t p = 0; p < part.particles.size(); ++p) wl[p] = w[part.particles[p]];
        local.internal_force(wl.data(), fl.data());
        shares += local.energy(wl.data());
        std::vector<ParticleId> owned(part.owned);
        for (std::size_t p = 0; p < part.owned; ++p) owned[p] = ParticleId(p);
        const std::vector<double> local_sums = local.stiffness_row_sums(owned);
        local.visit_tangent_rows(owned, [&](std::size_t p, const std::vector<ParticleId>& c, const std::vector<double>& v) {
          const ParticleId i = part.particles[p];
          std::vector<std::pair<ParticleId, double>> mapped;
          for (std::size_t q = 0; q < c.size(); ++q) mapped.emplace_back(part.particles[c[q]], v[q]);
          std::sort(mapped.begin(), mapped.end());
          CHECK(mapped.size() == cols[i].size());
          for (std::size_t q = 0; q < std::min(mapped.size(), cols[i].size()); ++q) {
            CHECK(mapped[q].first == cols[i][q]);
            worst_k = std::max(worst_k, std::abs(mapped[q].second - vals[i][q]) / sums[i]);
          }
        });
        for (std::size_t p = 0; p < part.owned; ++p) {
          const ParticleId i = part.particles[p];
          REQUIRE(seen.insert(i).second);
          worst = std::max(worst, std::abs(fl[p] - f[i]) / scale);
          worst_k = std::max(worst_k, std::abs(local_sums[p] - sums[i]) / sums[i]);
        }
      }
      CHECK(seen.size() == serial.dofs());
      CHECK(worst < 1e-12);
      CHECK(worst_k < 1e-12);
      CHECK(std::abs(shares - W) <= 1e-12 * std::abs(W));
    }
  }
}

TEST_CASE("a plate's rows cannot be limited beyond its fitted nodes", "[models][plate][partition]") {
  BoxGeometry box;
  box.dim = 2;
  box.max = {1.0, 1.0, 0.0};
  box.thickness = 0.01;
  PlateCloud p = make_plate_cloud(box, 0.125, PlateEdges{ss, ss, ss, ss}, 2);
  const Families fam = radius_families(p.cloud, 2.015 * 0.125);
  ThinPlateOptions o = steel();
  o.fitted_rows = 40;
  ThinPlateModel m(std::move(p), fam, o);
  CHECK_THROWS_AS(m.limit_rows(41, 20), std::logic_error);
  CHECK_THROWS_AS(m.limit_rows(30, 31), std::logic_error);
  CHECK_NOTHROW(m.limit_rows(40, 20));
}

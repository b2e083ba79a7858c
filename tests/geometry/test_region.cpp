// The particle nearest a point, and when a point is too far from every particle to be on the
// body (point probes and point regions refuse it).
#include <catch2/catch.hpp>

#include <array>
#include <cmath>

#include "perinom/geometry/lattice.hpp"
#include "perinom/geometry/region.hpp"

using namespace perinom;

namespace {

NearestParticle nearest(const PointCloud& c, std::array<double, 3> p) { return nearest_particle(c, p.data()); }

}  // namespace

TEST_CASE("a lattice's spacing is found at its interior, faces and corners", "[geometry]") {
  for (const int dim : {2, 3}) {
    BoxGeometry box;
    box.dim = dim;
    box.max = {5, 4, dim == 3 ? 3.0 : 0.0};
    const PointCloud c = make_lattice(box, 1.0);
    for (const auto& p : {std::array<double, 3>{2.5, 1.5, 1.5}, {0.5, 1.5, 1.5}, {0.5, 0.5, 0.5}, {4.5, 3.5, 2.5}}) {
      const NearestParticle n = nearest(c, p);
      CHECK(n.distance == Approx(0.0).margin(1e-12));
      CHECK(n.spacing == Approx(1.0));
    }
    // On the body: a face's centre, a corner (0.71 / 0.87 of a spacing away). Off it: beyond two.
    CHECK(outside_body(nearest(c, {2.5, 0.0, 1.5}), c).empty());
    CHECK(outside_body(nearest(c, {0.0, 0.0, 0.0}), c).empty());
    CHECK(outside_body(nearest(c, {2.5, -1.4, 1.5}), c).empty());  // 1.9 spacings
    const std::string far = outside_body(nearest(c, {2.5, -1.6, 1.5}), c);
    CHECK(far.find("is 2.1 m from the nearest particle (2.1 of its spacings; particle ") == 0);
    CHECK(far.find("outside the body or in a hole") != std::string::npos);
  }
}

TEST_CASE("one close neighbour does not shrink the spacing a far point is measured by", "[geometry]") {
  BoxGeometry box;
  box.dim = 2;
  box.max = {4, 4, 0};
  PointCloud c = make_lattice(box, 1.0);
  // A sliver's centroid next to the corner particle's: a hundredth of a spacing away.
  c.x.insert(c.x.end(), {0.51, 0.5});
  c.volume.push_back(c.volume[0]);
  const NearestParticle n = nearest(c, {-1.0, 0.5, 0.0});
  CHECK(n.id == 0);
  CHECK(n.spacing == Approx(1.0));  // its second nearest: a lattice neighbour, not the sliver
  CHECK(outside_body(n, c).empty());  // 1.5 spacings away: within two, not refused (0.01 would give 150)
}

TEST_CASE("a point midway between particles takes the lowest index, whatever rounding says", "[geometry]") {
  // The notched beam's supports at x = 25 and 150 mm fall midway between two columns at
  // every spacing; rounding chose a side, and the span was 122.5 mm at dx = 2.5 mm, 125 at
  // 1.25. The lowest index puts both half a spacing to the left: the span 125 at every dx.
  for (const double dx : {0.0025, 0.0025 / 1.4, 0.00125, 0.00125 / 1.4}) {
    BoxGeometry box;
    box.dim = 2;
    box.max = {0.175, 0.05, 0.0};
    const PointCloud c = make_lattice(box, dx);
    std::array<double, 2> at{};
    for (int k = 0; k < 2; ++k) {
      const std::array<double, 3> p{k == 0 ? 0.025 : 0.150, 0.0, 0.0};
      const NearestParticle n = nearest(c, p);
      const std::vector<ParticleId> ids = nearest_particles(c, p.data(), n);
      REQUIRE(ids.size() == 2);
      CHECK(n.id == ids[0]);
      CHECK(c.x[2 * ids[0]] < c.x[2 * ids[1]]);
      at[k] = c.x[2 * n.id];
    }
    CHECK(at[1] - at[0] == Approx(0.125).margin(1e-12));
    // A point on a particle is that particle alone, and a cell corner inside the body is
    // equally near four.
    const std::array<double, 3> on{c.x[0], c.x[1], 0.0}, corner{c.x[0] + 0.5 * c.spacing[0], c.x[1] + 0.5 * c.spacing[1], 0.0};
    CHECK(nearest_particles(c, on.data(), nearest(c, on)) == std::vector<ParticleId>{0});
    CHECK(nearest_particles(c, corner.data(), nearest(c, corner)).size() == 4);
  }
}

TEST_CASE("a tie is broken alike in metres and in millimetres", "[geometry]") {
  // A scene in mm took another particle than the same scene in m (rounding broke the tie).
  for (const double scale : {1.0, 1e-3, 1e3}) {
    BoxGeometry box;
    box.dim = 2;
    box.max = {0.1 * scale, 0.1 * scale, 0.0};
    const PointCloud c = make_lattice(box, 0.004 * scale);
    const std::array<double, 3> p{0.016 * scale, 0.072 * scale, 0.0};  // a corner of four cells
    const NearestParticle n = nearest(c, p);
    CHECK(nearest_particles(c, p.data(), n).size() == 4);
    CHECK(c.x[2 * n.id] / scale == Approx(0.014));
    CHECK(c.x[2 * n.id + 1] / scale == Approx(0.070));
  }
}

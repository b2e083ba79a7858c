// The pins of constraints: rigid_body, and the resultant that decides whether loads balance.
// The pins must remove every rigid mode and no deformation: on each cloud, the pinned values of
// the d (d + 1) / 2 rigid modes form a regular square matrix, and a jittered cloud or a slender
// one changes nothing of that.
#include <catch2/catch.hpp>

#include <cmath>

#include "perinom/core/error.hpp"
#include "perinom/geometry/region.hpp"
#include "perinom/models/rigid_body.hpp"
#include "../support/clouds.hpp"

using namespace perinom;

namespace {

/// The rank of the rigid modes' values at the pinned dofs (Gaussian elimination).
int pinned_rank(const PointCloud& c, const std::vector<RigidBodyPin>& pins) {
  const int d = c.dim, m = d * (d + 1) / 2;
  std::vector<std::vector<double>> rows;
  for (const auto& pin : pins)
    for (const int a : pin.components) {
      const double* x = c.point(pin.particle);
      std::vector<double> row(m, 0.0);
      row[a] = 1.0;
      // rotations about z (2-D), or x, y, z (3-D): (w x x)_a
      if (d == 2) row[2] = a == 0 ? -x[1] : x[0];
      else {
        if (a == 0) row[4] = x[2], row[5] = -x[1];
        if (a == 1) row[3] = -x[2], row[5] = x[0];
        if (a == 2) row[3] = x[1], row[4] = -x[0];
      }
      rows.push_back(row);
    }
  int rank = 0;
  for (int col = 0; col < m && rank < static_cast<int>(rows.size()); ++col) {
    std::size_t p = rank;
    for (std::size_t r = rank; r < rows.size(); ++r)
      if (std::abs(rows[r][col]) > std::abs(rows[p][col])) p = r;
    if (std::abs(rows[p][col]) < 1e-9) continue;
    std::swap(rows[p], rows[rank]);
    for (std::size_t r = rank + 1; r < rows.size(); ++r) {
      const double f = rows[r][col] / rows[rank][col];
      for (int k = 0; k < m; ++k) rows[r][k] -= f * rows[rank][k];
    }
    ++rank;
  }
  return rank;
}

std::size_t dofs(const std::vector<RigidBodyPin>& pins) {
  std::size_t n = 0;
  for (const auto& p : pins) n += p.components.size();
  return n;
}

}  // namespace

TEST_CASE("rigid body pins hold exactly the rigid modes in 2-D and 3-D", "[models][rigid_body]") {
  for (const int dim : {2, 3}) {
    for (const double jitter : {0.0, 0.4}) {
      INFO("dimension " << dim << ", jitter " << jitter);
      const PointCloud c = test::lattice(dim, dim == 2 ? 9 : 5, jitter);
      const auto pins = rigid_body_pins(c);
      CHECK(pins.size() == static_cast<std::size_t>(dim));
      CHECK(dofs(pins) == static_cast<std::size_t>(dim * (dim + 1) / 2));
      CHECK(pinned_rank(c, pins) == dim * (dim + 1) / 2);
      CHECK(pins[0].components.size() == static_cast<std::size_t>(dim));  // A: every component
    }
  }
}

TEST_CASE("rigid body pins of a slender body lie along its long axis", "[models][rigid_body]") {
  BoxGeometry box;
  box.dim = 3;
  box.max = {0.1, 0.01, 0.01};
  const PointCloud c = make_lattice(box, 0.0025, 0.0, 1);
  const auto pins = rigid_body_pins(c);
  REQUIRE(pins.size() == 3);
  // B at the far end of x, held in y and z; C at the far end of y (or z), held in the third axis.
  CHECK(std::abs(c.point(pins[1].particle)[0] - c.point(pins[0].particle)[0]) > 0.04);
  CHECK(pins[1].components == std::vector<int>{1, 2});
  CHECK(pins[2].components.size() == 1);
  CHECK(pinned_rank(c, pins) == 6);
}

TEST_CASE("a body one particle wide cannot hold rigid body pins", "[models][rigid_body]") {
  BoxGeometry box;
  box.dim = 2;
  box.max = {0.01, 0.001};
  CHECK_NOTHROW(rigid_body_pins(make_lattice(box, 0.001, 0.0, 1)));  // a row still holds 3 dofs in 2-D
  PointCloud one = make_lattice(box, 0.01, 0.0, 1);  // a single particle
  CHECK_THROWS_AS(rigid_body_pins(one), InputError);
}

TEST_CASE("the load resultant sees a net force and a couple", "[models][rigid_body]") {
  const PointCloud c = test::lattice(2, 4, 0.0);  // centroid (2, 2)
  std::vector<double> f(c.size() * 2, 0.0);
  CHECK(load_resultant(c, f).balanced(1e-8));  // unloaded
  f[0] = 1.0, f[(c.size() - 1) * 2] = -1.0;  // +x at (0.5, 0.5), -x at (3.5, 3.5): a couple
  LoadResultant r = load_resultant(c, f);
  CHECK(r.force[0] == 0.0);
  CHECK(r.moment[0] == Approx(3.0));  // -(y0 - 2) * 1 + (y1 - 2) * 1
  CHECK_FALSE(r.balanced(1e-8));
  f[(c.size() - 1) * 2] = 0.0, f[(c.size() - 4) * 2] = -1.0;  // -x at (0.5, 3.5): still a couple
  CHECK_FALSE(load_resultant(c, f).balanced(1e-8));
  f[(c.size() - 4) * 2] = 0.0, f[3 * 2] = -1.0;  // -x at (3.5, 0.5): on the same line, balanced
  CHECK(load_resultant(c, f).balanced(1e-8));
}

TEST_CASE("a point region selects the one particle nearest its point", "[geometry][rigid_body]") {
  const PointCloud c = test::lattice(2, 6, 0.3);
  Region r;
  r.is_side = false;
  r.is_point = true;
  r.point = {0.2, 5.9, 0.0};
  BoxGeometry box;
  const auto ids = select(r, box, c);
  REQUIRE(ids.size() == 1);
  for (std::size_t i = 0; i < c.size(); ++i)
    CHECK(std::hypot(c.x[i * 2] - 0.2, c.x[i * 2 + 1] - 5.9) >= std::hypot(c.x[ids[0] * 2] - 0.2, c.x[ids[0] * 2 + 1] - 5.9));
}

namespace {

/// Holds component a of every particle whose coordinate `along` is below `below`.
void hold_where(Loading& l, const PointCloud& c, int along, double below, int a) {
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c.point(i)[along] < below) l.fix(static_cast<std::int64_t>(i) * c.dim + a, 0.0);
}

ParticleId nearest_to(const PointCloud& c, std::array<double, 3> p) {
  Region r;
  r.is_side = false;
  r.is_point = true;
  r.point = p;
  return select(r, BoxGeometry{}, c).at(0);
}

}  // namespace

TEST_CASE("the free rigid motions of supports: none when held, the one left when not", "[models][rigid_body]") {
  SECTION("2-D: a face held across, then a point along it") {
    const PointCloud c = test::lattice(2, 9, 0.0);
    Loading l;
    CHECK(free_rigid_motions(c, l).size() == 3);  // nothing held
    hold_where(l, c, 0, 1.0, 0);                  // the left column in x
    auto free = free_rigid_motions(c, l);
    REQUIRE(free.size() == 1);
    CHECK_FALSE(free[0].turns);
    CHECK(std::abs(free[0].translation[0]) < 1e-12);
    CHECK(std::abs(free[0].translation[1]) > 0.5);
    l.fix(static_cast<std::int64_t>(nearest_to(c, {0.0, 0.0, 0.0})) * 2 + 1, 0.0);
    CHECK(free_rigid_motions(c, l).empty());
  }
  SECTION("2-D: one particle held in x and y leaves the turn about it") {
    const PointCloud c = test::lattice(2, 9, 0.3);
    Loading l;
    const ParticleId i = nearest_to(c, {2.0, 7.0, 0.0});
    l.fix(static_cast<std::int64_t>(i) * 2, 0.0), l.fix(static_cast<std::int64_t>(i) * 2 + 1, 0.0);
    const auto free = free_rigid_motions(c, l);
    REQUIRE(free.size() == 1);
    CHECK(free[0].turns);
    CHECK(free[0].point[0] == Approx(c.point(i)[0]).margin(1e-9));
    CHECK(free[0].point[1] == Approx(c.point(i)[1]).margin(1e-9));
  }
  SECTION("3-D: a bar held by its end faces and two points on one line turns about that line") {
    BoxGeometry box;
    box.dim = 3;
    box.max = {0.1, 0.02, 0.02};
    const PointCloud c = make_lattice(box, 0.0025, 0.0, 1);
    Loading l;
    hold_where(l, c, 0, 0.0025, 0);
    for (std::size_t i = 0; i < c.size(); ++i)
      if (c.point(i)[0] > 0.0975) l.fix(static_cast<std::int64_t>(i) * 3, 0.0);
    const ParticleId P = nearest_to(c, {0.0, 0.0, 0.0}), Q = nearest_to(c, {0.1, 0.0, 0.0});
    for (const ParticleId i : {P, Q})
      for (const int a : {1, 2}) l.fix(static_cast<std::int64_t>(i) * 3 + a, 0.0);
    const auto free = free_rigid_motions(c, l);
    REQUIRE(free.size() == 1);
    CHECK(free[0].turns);
    CHECK(std::abs(free[0].rotation[1]) < 1e-9 * std::abs(free[0].rotation[0]));
    CHECK(std::abs(free[0].rotation[2]) < 1e-9 * std::abs(free[0].rotation[0]));
    CHECK(free[0].point[1] == Approx(c.point(P)[1]).margin(1e-12));  // the axis through P and Q
    CHECK(free[0].point[2] == Approx(c.point(P)[2]).margin(1e-12));
    // A point off that line held in z holds the turn.
    l.fix(static_cast<std::int64_t>(nearest_to(c, {0.0, 0.02, 0.0})) * 3 + 2, 0.0);
    CHECK(free_rigid_motions(c, l).empty());
  }
}

TEST_CASE("the free rigid deflections of a plate: a hinge line turns, a clamp or two edges hold",
          "[models][rigid_body]") {
  // A 0.4 x 0.2 m plate (dx 0.02 m, two ghost layers) with w = 0 on its supported edges' nodes,
  // as plate_problem.cpp sets them, and the ghosts' mirrors (a clamped edge's symmetric).
  BoxGeometry box;
  box.dim = 2;
  box.max = {0.4, 0.2, 0.0};
  const EdgeSupport o = EdgeSupport::free, s = EdgeSupport::simply_supported, c = EdgeSupport::clamped;
  auto free = [&](const PlateEdges& edges) {
    const PlateCloud plate = make_plate_cloud(box, 0.02, edges, 2);
    Loading l;
    for (int e = 0; e < 4; ++e)
      if (edges[e] != EdgeSupport::free)
        for (const ParticleId i : plate.edge_nodes(e)) l.fix(i, 0.0);
    return free_plate_motions(plate, l);
  };
  CHECK(free({o, o, o, o}).size() == 3);  // a translation along z and two turns
  const auto hinge = free({s, o, o, o});  // the edge x = 0 simply supported: the turn about it
  REQUIRE(hinge.size() == 1);
  CHECK(hinge[0].turns);
  CHECK(std::abs(hinge[0].rotation[0]) < 1e-9 * std::abs(hinge[0].rotation[1]));
  CHECK(hinge[0].rotation[2] == 0.0);
  CHECK(hinge[0].point[0] == Approx(0.0).margin(1e-12));
  const auto bottom = free({o, o, s, o});  // y = 0: the turn about the x axis
  REQUIRE(bottom.size() == 1);
  CHECK(std::abs(bottom[0].rotation[1]) < 1e-9 * std::abs(bottom[0].rotation[0]));
  CHECK(bottom[0].point[1] == Approx(0.0).margin(1e-12));
  CHECK(free({c, o, o, o}).empty());  // a cantilever plate: the clamp's mirror holds the turn
  CHECK(free({s, s, o, o}).empty());  // two opposite edges
  CHECK(free({s, o, s, o}).empty());  // two adjacent edges
  CHECK(free({s, s, s, s}).empty());
}

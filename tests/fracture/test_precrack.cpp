// Precracks cut exactly the bonds that cross them: checked against a direct computation for
// axis-aligned cracks, in 2-D and 3-D, on jittered lattices.
#include <catch2/catch.hpp>

#include <set>
#include <stdexcept>

#include "../support/clouds.hpp"
#include "perinom/fracture/precrack.hpp"
#include "perinom/geometry/lattice.hpp"
#include "perinom/geometry/region.hpp"
#include "perinom/neighbors/bond_graph.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

namespace {

using Pair = std::pair<ParticleId, ParticleId>;

/// The bonds crossing the plane x_axis = level inside the box [lo, hi] of the other axes,
/// from the crossing point's coordinates (an independent route to the same set).
std::set<Pair> crossing_axis_aligned(const PointCloud& c, const Families& f, int axis, double level, const double* lo,
                                     const double* hi) {
  std::set<Pair> out;
  const int d = c.dim;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (Offset k = f.begin(i); k < f.end(i); ++k) {
      const std::size_t j = f.neighbors[k];
      const double si = c.x[i * d + axis] - level, sj = c.x[j * d + axis] - level;
      if (!(si * sj < 0.0)) continue;
      const double t = si / (si - sj);
      bool inside = true;
      for (int a = 0; a < d; ++a) {
        if (a == axis) continue;
        const double xa = c.x[i * d + a] + t * (c.x[j * d + a] - c.x[i * d + a]);
        inside = inside && xa >= lo[a] && xa <= hi[a];
      }
      if (inside) out.insert({std::min<ParticleId>(i, j), std::max<ParticleId>(i, j)});
    }
  return out;
}

}  // namespace

TEST_CASE("a 2-D precrack segment cuts exactly the bonds that cross it", "[fracture]") {
  const PointCloud c = test::lattice(2, 12, 0.2);
  const Families f = radius_families(c, 3.015);
  // A notch from the left edge to the centre, at mid-height (between particle rows).
  Precrack notch;
  notch.origin = {-1.0, 6.0, 0.0};
  notch.edge1 = {7.0, 0.0, 0.0};
  const auto cut = bonds_crossing(c, f, {notch});
  const double lo[2] = {-1.0, 0.0}, hi[2] = {6.0, 0.0};
  const std::set<Pair> expected = crossing_axis_aligned(c, f, 1, 6.0, lo, hi);
  REQUIRE(!expected.empty());
  CHECK(std::set<Pair>(cut.begin(), cut.end()) == expected);
  CHECK(cut.size() == expected.size());  // each bond once
  // Broken on the graph, no live bond crosses the notch any more.
  BondGraph g(f);
  for (const auto& [i, j] : cut) g.break_bond(i, j);
  for (std::size_t i = 0; i < g.rows(); ++i)
    g.for_each_live(i, [&](Offset, ParticleId j) { CHECK_FALSE(crosses(notch, 2, c.point(i), c.point(j))); });
}

TEST_CASE("a 3-D precrack rectangle cuts exactly the bonds that cross it", "[fracture]") {
  const PointCloud c = test::lattice(3, 8, 0.2);
  const Families f = radius_families(c, 2.015);
  // In the plane z = 4, over x in [0, 5] and y in [1, 6]; given with a corner and two edges.
  Precrack crack;
  crack.origin = {5.0, 1.0, 4.0};
  crack.edge1 = {-5.0, 0.0, 0.0};
  crack.edge2 = {0.0, 5.0, 0.0};
  const auto cut = bonds_crossing(c, f, {crack});
  const double lo[3] = {0.0, 1.0, 0.0}, hi[3] = {5.0, 6.0, 0.0};
  const std::set<Pair> expected = crossing_axis_aligned(c, f, 2, 4.0, lo, hi);
  REQUIRE(!expected.empty());
  CHECK(std::set<Pair>(cut.begin(), cut.end()) == expected);
}

TEST_CASE("a bond ending on the crack line is not cut, and degenerate cracks are refused", "[fracture]") {
  Precrack seg;
  seg.origin = {0.0, 1.0, 0.0};
  seg.edge1 = {2.0, 0.0, 0.0};
  const double on[2] = {1.0, 1.0}, above[2] = {1.0, 2.0}, below[2] = {1.0, 0.5}, beyond[2] = {3.0, 0.5},
               far[2] = {3.0, 2.0};
  CHECK_FALSE(crosses(seg, 2, on, above));
  CHECK(crosses(seg, 2, below, above));
  CHECK_FALSE(crosses(seg, 2, beyond, far));  // crosses the line beyond the segment's end
  const double end_below[2] = {2.0, 0.5}, end_above[2] = {2.0, 1.5};
  CHECK(crosses(seg, 2, end_below, end_above));  // through the end point: cut
  Precrack zero;
  CHECK_THROWS_AS(crosses(zero, 2, below, above), std::invalid_argument);
  Precrack flat;
  flat.edge1 = {1.0, 0.0, 0.0};
  flat.edge2 = {2.0, 0.0, 0.0};
  const double p[3] = {0.0, 0.0, -1.0}, q[3] = {0.0, 0.0, 1.0};
  CHECK_THROWS_AS(crosses(flat, 3, p, q), std::invalid_argument);
}

TEST_CASE("mirror notches ending where bonds cross their line cut mirror bonds", "[fracture]") {
  // Notches that end exactly where bonds between two particle columns cross their line:
  // Kalthoff-Winkler's (from x = -2.5 mm to 50 mm at y = +-25 mm, dx = 2.5 mm), and SENT's
  // mirrored about its crack line (from x = -0.01 mm to 0.5 mm at y = 0.5 mm, dx = 0.05 mm).
  // Rounding cut such bonds at one notch and not at its mirror (Kalthoff's damage 0.07 apart
  // at the start, 0.86 after the run).
  struct Case {
    double x0, x1, y, dx, half_height;
  };
  for (const Case k : {Case{-0.0025, 0.05, 0.025, 0.0025, 0.1}, Case{-1e-5, 5e-4, 5e-4, 5e-5, 1e-3}}) {
    INFO("notch from x = " << k.x0 << " to " << k.x1 << " at y = +-" << k.y);
    BoxGeometry box;
    box.dim = 2;
    box.min = {0.0, -k.half_height, 0.0};
    box.max = {2.0 * k.x1, k.half_height, 0.0};
    const PointCloud c = make_lattice(box, k.dx, 0.0, 1);
    const Families f = radius_families(c, 3.015 * k.dx);
    Precrack upper, lower;
    upper.origin = {k.x0, k.y, 0.0}, upper.edge1 = {k.x1 - k.x0, 0.0, 0.0};
    lower.origin = {k.x0, -k.y, 0.0}, lower.edge1 = {k.x1 - k.x0, 0.0, 0.0};
    const auto up = bonds_crossing(c, f, {upper}), down = bonds_crossing(c, f, {lower});
    // Each cut bond of the upper notch, mirrored in y = 0, is a cut bond of the lower one.
    const auto mirror = [&](ParticleId i) {
      const double m[2] = {c.x[2 * i], -c.x[2 * i + 1]};
      return nearest_particle(c, m).id;
    };
    std::set<Pair> mirrored, lower_set;
    for (const auto& [i, j] : up) mirrored.insert({std::min(mirror(i), mirror(j)), std::max(mirror(i), mirror(j))});
    for (const auto& [i, j] : down) lower_set.insert({std::min(i, j), std::max(i, j)});
    CHECK(up.size() == down.size());
    CHECK(mirrored == lower_set);
    // The bonds through the tip are cut (the end included); those past it are not.
    const double h = k.dx / 2;
    const double a[2] = {k.x1 - h, k.y - h}, b[2] = {k.x1 + h, k.y + h};
    CHECK(crosses(upper, 2, a, b));
    const double c1[2] = {k.x1 + h, k.y - h}, c2[2] = {k.x1 + 3 * h, k.y + h};
    CHECK_FALSE(crosses(upper, 2, c1, c2));
  }
}

TEST_CASE("particles_on finds the particles a precrack passes through, and only those", "[fracture]") {
  // A crack along a particle row cuts only the bonds whose ends are strictly either side:
  // the row's own bonds stay, which users were not told (precrack_row_note).
  const PointCloud c = test::lattice(2, 8, 0.0);  // centres at k + 0.5
  Precrack along;
  along.origin = {0.0, 3.5, 0.0};
  along.edge1 = {4.0, 0.0, 0.0};  // through (0.5, 3.5) ... (3.5, 3.5)
  const std::vector<ParticleId> on = particles_on(c, along);
  REQUIRE(on.size() == 4);
  for (const ParticleId i : on) {
    CHECK(c.point(i)[1] == Approx(3.5));
    CHECK(c.point(i)[0] < 4.0);
  }
  Precrack between = along;
  between.origin[1] = 4.0;  // between rows
  CHECK(particles_on(c, between).empty());
  // In 3-D: a rectangle in the plane z = 2.5 through the particles with x, y < 2.
  const PointCloud c3 = test::lattice(3, 5, 0.0);
  Precrack plane;
  plane.origin = {0.0, 0.0, 2.5};
  plane.edge1 = {2.0, 0.0, 0.0};
  plane.edge2 = {0.0, 2.0, 0.0};
  CHECK(particles_on(c3, plane).size() == 4);
  plane.origin[2] = 3.0;
  CHECK(particles_on(c3, plane).empty());
}

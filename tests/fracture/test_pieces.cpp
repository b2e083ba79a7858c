// The pieces a cracked body falls into (body_pieces), as a load path that stops unbalanced
// reads them: a lattice cut through by breaking every bond across a line falls in two, a
// detached particle belongs to none, and a rigid-motion check on each piece sees only its
// own supports.
#include <catch2/catch.hpp>

#include "../support/clouds.hpp"
#include "perinom/fracture/pieces.hpp"
#include "perinom/models/rigid_body.hpp"
#include "perinom/neighbors/bond_graph.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

TEST_CASE("a lattice cut across falls into two pieces, each checked for its own supports", "[fracture][pieces]") {
  const PointCloud c = test::lattice(2, 10, 0.0);  // particles at 0.5 .. 9.5
  BondGraph g(radius_families(c, 3.015));
  REQUIRE(body_pieces(g, {}).count == 1);
  // Break every bond across x = 5 but those of the top row: still one piece.
  auto cut = [&](bool top_too) {
    for (std::size_t i = 0; i < c.size(); ++i)
      for (Offset k = g.begin(i); k < g.end(i); ++k) {
        const ParticleId j = g.col(k);
        const bool across = (c.point(i)[0] < 5.0) != (c.point(j)[0] < 5.0);
        const bool top = c.point(i)[1] > 9.0 && c.point(j)[1] > 9.0;
        if (across && (top_too || !top)) g.break_bond(static_cast<ParticleId>(i), j);
      }
  };
  cut(false);
  CHECK(body_pieces(g, {}).count == 1);
  cut(true);
  Pieces p = body_pieces(g, {});
  REQUIRE(p.count == 2);
  for (std::size_t i = 0; i < c.size(); ++i) CHECK(p.piece[i] == (c.point(i)[0] < 5.0 ? 0 : 1));
  // A detached particle is apart: -1, and the pieces stay two.
  p = body_pieces(g, {static_cast<ParticleId>(c.size() - 1)});
  CHECK(p.count == 2);
  CHECK(p.piece[c.size() - 1] == -1);
  // The left column held in x and y holds the left piece; the right piece is free.
  Loading l;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c.point(i)[0] < 1.0) l.fix(static_cast<std::int64_t>(i) * 2, 0.0), l.fix(static_cast<std::int64_t>(i) * 2 + 1, 0.0);
  CHECK(free_rigid_motions(c, l).empty());
  std::vector<std::uint8_t> left(c.size()), right(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) left[i] = p.piece[i] == 0, right[i] = p.piece[i] == 1;
  CHECK(free_rigid_motions(c, l, left).empty());
  CHECK(free_rigid_motions(c, l, right).size() == 3);
}

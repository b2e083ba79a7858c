#include <catch2/catch.hpp>

#include <cmath>

#include "perinom/geometry/surface.hpp"

using namespace perinom;

namespace {

std::size_t nearest(const PointCloud& c, double x, double y) {
  std::size_t best = 0;
  double d2 = INFINITY;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double e = std::pow(c.x[2 * i] - x, 2) + std::pow(c.x[2 * i + 1] - y, 2);
    if (e < d2) d2 = e, best = i;
  }
  return best;
}

}  // namespace

TEST_CASE("faces get their normal over the spacing, convex corners the sum", "[geometry]") {
  BoxGeometry box;
  box.dim = 2;
  box.max = {10, 20, 0};
  const PointCloud c = make_lattice(box, 1.0);
  const Surface s = find_surface(box, c, 3.0);
  const double* m = s.normal_over_h.data();
  const std::size_t left = nearest(c, 0.5, 10.5), top_left = nearest(c, 0.5, 19.5), inside = nearest(c, 5.5, 10.5);
  CHECK(m[2 * left] == -1.0);
  CHECK(m[2 * left + 1] == 0.0);
  CHECK(m[2 * top_left] == -1.0);  // (-1, 1): the sum of the left and top normals
  CHECK(m[2 * top_left + 1] == 1.0);
  CHECK(m[2 * inside] == 0.0);
  CHECK(m[2 * inside + 1] == 0.0);
  CHECK(s.on_surface[left] == 1);
  CHECK(s.on_surface[inside] == 0);
  // The band: within 3 of a face. Interior columns 3.5 ... 6.5 and rows 3.5 ... 16.5.
  CHECK(s.interior.size() == 4 * 14);
  CHECK(s.band.size() + s.interior.size() == c.size());
  CHECK(s.in_band[nearest(c, 2.5, 10.5)] == 1);
  CHECK(s.in_band[nearest(c, 3.5, 10.5)] == 0);
}

TEST_CASE("a hole has its own surface and band, with normals pointing into it", "[geometry]") {
  BoxGeometry box;
  box.dim = 2;
  box.max = {40, 40, 0};
  box.holes.push_back({Hole::Shape::circle, {20, 20, 0}, 5.0, 2});
  const PointCloud c = make_lattice(box, 1.0);
  const Surface s = find_surface(box, c, 3.0);
  const std::size_t rim = nearest(c, 25.5, 20.5), beyond = nearest(c, 29.5, 20.5), far = nearest(c, 30.5, 20.5);
  CHECK(s.on_surface[rim] == 1);
  // The outward normal of the body at the hole's right rim points left, into the hole.
  CHECK(s.normal_over_h[2 * rim] < -0.9);
  CHECK(std::abs(s.normal_over_h[2 * rim + 1]) < 0.2);
  CHECK(s.on_surface[beyond] == 0);
  CHECK(s.in_band[nearest(c, 27.5, 20.5)] == 1);  // 2.7 from the hole
  CHECK(s.in_band[far] == 0);                     // 5.7 from the hole, 9.5 from the faces
  // Every particle near the hole's boundary is a surface particle; none is inside the hole.
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double r = std::hypot(c.x[2 * i] - 20, c.x[2 * i + 1] - 20);
    REQUIRE(r >= 5.0);
    if (r < 6.0) CHECK(s.on_surface[i] == 1);
  }
}

TEST_CASE("3-D box edges and vertices sum two and three face normals", "[geometry]") {
  BoxGeometry box;
  box.dim = 3;
  box.max = {6, 6, 6};
  const PointCloud c = make_lattice(box, 1.0);
  const Surface s = find_surface(box, c, 1.0);
  const double* vertex = s.normal_over_h.data();  // particle 0 sits at the (min, min, min) vertex
  CHECK(vertex[0] == -1.0);
  CHECK(vertex[1] == -1.0);
  CHECK(vertex[2] == -1.0);
  std::size_t on = 0;
  for (auto f : s.on_surface) on += f;
  CHECK(on == 6 * 6 * 6 - 4 * 4 * 4);
}

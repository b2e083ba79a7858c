// Meshes whose elements are wrong in a way the divergence theorem does not see, through the
// perinom program: each ran to exit 0 with a wrong answer until refused. A collapsed
// quadrangle (a node listed twice) ran 16% off the uniform-tension patch test; a seam of
// unmerged nodes doubled a plate's stretch. A node no element uses is no part of the body.
#include <array>
#include <map>
#include <vector>

#include "../support/cli_run.hpp"

namespace {

/// A 10 mm square of n x n quadrangles in gmsh's format 4.1: node (i, j) at (i, j) * 10 mm / n
/// has tag j (n + 1) + i + 1; groups left, right, bottom, top (lines) and body (the quadrangles).
struct Plate {
  int n;
  std::map<long, std::array<double, 3>> nodes;
  std::vector<std::vector<long>> quads;
  std::vector<std::vector<long>> sides[4];

  explicit Plate(int cells) : n(cells) {
    const double h = 0.01 / n;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) nodes[tag(i, j)] = {i * h, j * h, 0.0};
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) quads.push_back({tag(i, j), tag(i + 1, j), tag(i + 1, j + 1), tag(i, j + 1)});
    for (int k = 0; k < n; ++k) {
      sides[0].push_back({tag(0, k), tag(0, k + 1)});
      sides[1].push_back({tag(n, k), tag(n, k + 1)});
      sides[2].push_back({tag(k, 0), tag(k + 1, 0)});
      sides[3].push_back({tag(k, n), tag(k + 1, n)});
    }
  }
  long tag(int i, int j) const { return j * (n + 1) + i + 1; }

  std::string msh() const {
    std::ostringstream s;
    s.precision(17);
    s << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n5\n1 1 \"left\"\n1 2 \"right\"\n1 3 \"bottom\"\n"
      << "1 4 \"top\"\n2 5 \"body\"\n$EndPhysicalNames\n$Entities\n0 4 1 0\n";
    for (int c = 1; c <= 4; ++c) s << c << " 0 0 0 0.01 0.01 0 1 " << c << " 0\n";
    s << "1 0 0 0 0.01 0.01 0 1 5 0\n$EndEntities\n$Nodes\n1 " << nodes.size() << " " << nodes.begin()->first << " "
      << nodes.rbegin()->first << "\n2 1 0 " << nodes.size() << "\n";
    for (const auto& v : nodes) s << v.first << "\n";
    for (const auto& v : nodes) s << v.second[0] << " " << v.second[1] << " " << v.second[2] << "\n";
    const std::size_t lines = 4 * static_cast<std::size_t>(n), total = quads.size() + lines;
    s << "$EndNodes\n$Elements\n5 " << total << " 1 " << total << "\n2 1 3 " << quads.size() << "\n";
    long element = 1;
    for (const auto& q : quads) s << element++ << " " << q[0] << " " << q[1] << " " << q[2] << " " << q[3] << "\n";
    for (int c = 0; c < 4; ++c) {
      s << "1 " << c + 1 << " 1 " << sides[c].size() << "\n";
      for (const auto& l : sides[c]) s << element++ << " " << l[0] << " " << l[1] << "\n";
    }
    s << "$EndElements\n";
    return s.str();
  }
};

const std::string scene = R"(name: plate
dimension: 2
geometry: {mesh: plate.msh, thickness: 0.001}
discretization: {dx: 0.0017, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 200.0e9, nu: 0.3, density: 7800.0, plane: strain}
boundary:
  - {region: {group: left}, fix: [x], at: face}
  - {region: {group: bottom}, fix: [y], at: face}
  - {region: {group: right}, traction: [1.0e6, 0]}
)";

Outcome check(const Plate& plate) {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << scene;
  std::ofstream(dir.path / "plate.msh") << plate.msh();
  return perinom(dir, "check scene.yaml");
}

}  // namespace

TEST_CASE("the generated plate mesh passes check", "[cli][mesh]") {
  const Outcome o = check(Plate(6));
  INFO("stderr: " << o.err);
  CHECK(o.exit_code == 0);
}

TEST_CASE("a mesh element that lists a node twice is refused naming its gmsh tag and the node", "[cli][mesh]") {
  // The tester's quadrangle 1 2 13 13: a triangle with a zero-length edge, read as a quadrangle.
  Plate p(6);
  p.quads[0][3] = p.quads[0][2];
  require_one_clear_error(check(p), {"geometry.mesh", "plate.msh: line", "element 1 lists node 9 twice",
                                     "a collapsed element is refused"});
}

TEST_CASE("two mesh nodes at one point are refused naming their tags and the position", "[cli][mesh]") {
  // The column of quadrangles at i = 3 takes its own copies of its left nodes: a seam. The
  // divergence theorem holds (its two sides' facets cancel) and a pulled plate stretched
  // 2.06 times as far.
  Plate p(6);
  for (int j = 0; j < p.n; ++j)
    for (long& v : p.quads[j * p.n + 3])
      if (v == p.tag(3, j) || v == p.tag(3, j + 1)) {
        p.nodes[v + 100] = p.nodes[v];
        v += 100;
      }
  require_one_clear_error(check(p), {"geometry.mesh", "nodes 4 and 104 are both at (0.005, 0, 0)",
                                     "Coherence Mesh", "removeDuplicateNodes"});
}

TEST_CASE("a node off the plane that no element uses leaves a 2-D mesh in its plane", "[cli][mesh]") {
  // Such a node (a construction point of the .geo) failed the plane check: "z spans 0 to 0.01 m".
  Plate p(6);
  p.nodes[1000] = {0.005, 0.005, 0.01};
  const Outcome o = check(p);
  INFO("stderr: " << o.err);
  CHECK(o.exit_code == 0);
}

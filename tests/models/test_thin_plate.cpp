// The nonlocal Kirchhoff plate (THEORY sec. 7): force, energy and stiffness agree, the
// curvature is exact for quadratic deflections, scenes build only the operators they use, and
// the square plate matches Timoshenko's centre deflections.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "../support/clouds.hpp"
#include "perinom/core/error.hpp"
#include "perinom/models/thin_plate.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/adr.hpp"

using namespace perinom;

namespace {

BoxGeometry square(double a) {
  BoxGeometry box;
  box.dim = 2;
  box.max = {a, a, 0.0};
  box.thickness = 0.01;
  return box;
}

ThinPlateOptions steel(double c_hg) {
  ThinPlateOptions o;
  o.E = 210e9, o.nu = 0.3, o.thickness = 0.01, o.density = 7800.0, o.stabilization = c_hg;
  return o;
}

/// A plate of n x n cells on [0, 1]^2 with the given edges and horizon ratio.
std::unique_ptr<ThinPlateModel> plate(int n, const PlateEdges& edges, double ratio, double c_hg) {
  const double dx = 1.0 / n;
  PlateCloud cloud = make_plate_cloud(square(1.0), dx, edges, static_cast<int>(ratio));
  const Families f = radius_families(cloud.cloud, ratio * dx);
  return std::make_unique<ThinPlateModel>(std::move(cloud), f, steel(c_hg));
}

constexpr EdgeSupport ss = EdgeSupport::simply_supported, cl = EdgeSupport::clamped, fr = EdgeSupport::free;

}  // namespace

TEST_CASE("plate force equals the derivative of the plate energy, stabilization included", "[models][plate]") {
  for (const PlateEdges edges : {PlateEdges{ss, ss, ss, ss}, PlateEdges{cl, cl, cl, cl}, PlateEdges{fr, cl, ss, fr}}) {
    auto m = plate(8, edges, 2.015, 0.5);
    const std::size_t n = m->dofs();
    const std::vector<double> w = test::random_field(n, 1e-3, 11);
    std::vector<double> f(n);
    m->internal_force(w.data(), f.data());
    double fmax = 0.0;
    for (const double x : f) fmax = std::max(fmax, std::abs(x));
    const double h = 1e-7;
    for (const std::size_t k : {std::size_t(0), std::size_t(5), n / 2, n - 3}) {
      std::vector<double> wp = w, wm = w;
      wp[k] += h, wm[k] -= h;
      const double fd = (m->energy(wp.data()) - m->energy(wm.data())) / (2 * h);
      CHECK(std::abs(fd - f[k]) <= 1e-6 * fmax);
    }
  }
}

TEST_CASE("plate stiffness rows times w equal the internal force, and are symmetric", "[models][plate]") {
  auto m = plate(9, PlateEdges{cl, ss, ss, fr}, 2.015, 0.5);
  const std::size_t n = m->dofs();
  const std::vector<double> w = test::random_field(n, 1.0, 5);
  std::vector<double> f(n), Kw(n, 0.0);
  m->internal_force(w.data(), f.data());
  std::vector<std::vector<std::pair<ParticleId, double>>> rows(n);
  m->visit_tangent_rows([&](std::size_t r, const std::vector<ParticleId>& cols, const std::vector<double>& v) {
    for (std::size_t k = 0; k < cols.size(); ++k) Kw[r] += v[k] * w[cols[k]], rows[r].emplace_back(cols[k], v[k]);
  });
  double fmax = 0.0;
  for (const double x : f) fmax = std::max(fmax, std::abs(x));
  for (std::size_t r = 0; r < n; ++r) REQUIRE(std::abs(Kw[r] - f[r]) <= 1e-9 * fmax);
  auto entry = [&](std::size_t r, ParticleId c) {
    for (const auto& e : rows[r]) if (e.first == c) return e.second;
    return 0.0;
  };
  double kmax = 0.0, asym = 0.0;
  for (std::size_t r = 0; r < n; ++r)
    for (const auto& e : rows[r]) kmax = std::max(kmax, std::abs(e.second)), asym = std::max(asym, std::abs(e.second - entry(e.first, static_cast<ParticleId>(r))));
  CHECK(asym <= 1e-10 * kmax);
}

TEST_CASE("plate curvature is exact for quadratic deflections, edge nodes included", "[models][plate]") {
  // Free edges: no ghosts, so every node's fit sees the quadratic itself.
  auto m = plate(10, PlateEdges{fr, fr, fr, fr}, 2.5, 0.5);
  const PointCloud& c = m->plate().cloud;
  const std::size_t n = m->dofs();
  std::vector<double> w(n), kappa(n * 3);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = c.x[2 * i], y = c.x[2 * i + 1];
    w[i] = 0.3 + 0.1 * x - 0.2 * y + 0.5 * 1.5 * x * x - 0.7 * x * y + 0.5 * 2.0 * y * y;
  }
  m->curvature(w.data(), kappa.data());
  for (std::size_t i = 0; i < n; ++i) {
    REQUIRE(kappa[3 * i] == Approx(1.5).margin(1e-9));
    REQUIRE(kappa[3 * i + 1] == Approx(-0.7).margin(1e-9));
    REQUIRE(kappa[3 * i + 2] == Approx(2.0).margin(1e-9));
  }
  // A quadratic carries no stabilization energy: the energy is the bending energy alone.
  double bending = 0.0;
  const double D = m->rigidity(), nu = 0.3;
  for (std::size_t i = 0; i < n; ++i)
    bending += 0.5 * m->plate().area[i] * D * (1.5 * 1.5 + 2.0 * 2.0 + 2 * nu * 1.5 * 2.0 + 2 * (1 - nu) * 0.49);
  CHECK(m->energy(w.data()) == Approx(bending).epsilon(1e-9));
}

namespace {

std::string run_check(const std::string& scene) {
  const std::string cmd = "'" PERINOM_EXE "' check '" PERINOM_SOURCE_DIR "/examples/" + scene + "' 2>&1";
  std::string out;
  FILE* pipe = popen(cmd.c_str(), "r");
  char buf[512];
  while (pipe && fgets(buf, sizeof buf, pipe)) out += buf;
  if (pipe) pclose(pipe);
  return out;
}

Problem example(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return build_problem(read_scene(PERINOM_SOURCE_DIR "/examples/" + name, overrides));
}

bool lists(const Model& m, const std::string& what) {
  for (const auto& e : m.memory())
    if (e.first.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("a plate scene builds no elasticity operators and an elasticity scene no Hessian", "[models][plate][cli]") {
  const Problem plate = example("thin_plate_clamped.yaml");
  REQUIRE(dynamic_cast<const ThinPlateModel*>(plate.model.get()) != nullptr);
  CHECK(lists(plate.as<ThinPlateModel>(), "second-order operator"));
  CHECK_FALSE(lists(plate.as<ThinPlateModel>(), "gradient operator G"));
  const Problem solid = example("uniaxial_compression.yaml");
  CHECK(dynamic_cast<const ThinPlateModel*>(solid.model.get()) == nullptr);
  REQUIRE(dynamic_cast<const CorrespondenceModel*>(solid.model.get()) != nullptr);
  // The demo runs the consistent formulation with the second-order fit's gradient: G and the
  // second-order stabilization, but no Hessian is kept.
  CHECK(lists(*solid.model, "gradient G"));
  CHECK_FALSE(lists(*solid.model, "second-order operator"));
  // And `perinom check` says so.
  const std::string p = run_check("thin_plate_clamped.yaml"), e = run_check("uniaxial_compression.yaml");
  CHECK(p.find("second-order operator (g, h)") != std::string::npos);
  CHECK(p.find("gradient operator G and G^T ") == std::string::npos);
  CHECK(p.find("not assembled: gradient operator G and stabilization S of elasticity") != std::string::npos);
  CHECK(e.find("gradient G (second-order fit)") != std::string::npos);
  CHECK(e.find("second-order operator") == std::string::npos);
  CHECK(e.find("not assembled: Hessian") != std::string::npos);
}

TEST_CASE("square plate centre deflection within 2% (simply supported) and 3% (clamped) of Timoshenko at 41 x 41",
          "[models][plate][verification]") {
  const double D0 = 210e9 * 1e-6 / (12.0 * (1.0 - 0.09)), qa4 = 1000.0 * std::pow(0.5, 4);
  const std::pair<const char*, double> cases[] = {{"thin_plate_simply_supported.yaml", 0.00406},
                                                  {"thin_plate_clamped.yaml", 0.00126}};
  for (const auto& c : cases) {
    Problem p = example(c.first);
    REQUIRE(p.cloud.size() == 41 * 41);
    std::vector<double> w(p.physics().dofs(), 0.0);
    AdrOptions o;
    o.tolerance = 1e-8, o.displacement_tolerance = 1e-10;
    const SolveReport rep = solve_adr(p.physics(), p.loading, o, w);
    REQUIRE(rep.converged);
    const double centre = w[p.probes.at(0).particles.at(0)], reference = c.second * qa4 / D0;
    INFO(c.first << ": " << centre << " against " << reference);
    CHECK(std::abs(centre / reference - 1.0) < (c.second > 0.003 ? 0.02 : 0.03));
  }
}

TEST_CASE("a pressure on a side of a plate loads that edge's nodes at every spacing", "[models][plate]") {
  // The plate's nodes sit on its edges: the particle lattice's rule (the layer within one
  // spacing of the face) met the next row at exactly one spacing and took it by rounding at
  // some spacings (the free edge's deflection 4.1, 5.9, 8.0 and 1.1 um at dx = 12.5, 50, 25
  // and 10 mm, where the edge strip's load scales as dx).
  for (const double dx : {0.05, 0.025, 0.0125, 0.01}) {
    INFO("dx = " << dx);
    const Problem p = example("thin_plate_simply_supported.yaml",
                              {"discretization.dx=" + std::to_string(dx), "boundary.3={region: top, pressure: 1000.0}",
                               "boundary.4.pressure=0.0"});
    double total = 0.0;
    std::size_t loaded = 0;
    for (std::size_t i = 0; i < p.loading.force.size(); ++i)
      if (p.loading.force[i] != 0.0) total += p.loading.force[i], ++loaded;
    CHECK(total == Approx(1000.0 * 0.5 * dx / 2.0).epsilon(1e-12));  // q times the edge strip, 0.5 m by dx / 2
    CHECK(loaded == std::size_t(std::lround(0.5 / dx)) + 1);           // the edge's nodes, corners included
  }
}

TEST_CASE("a plate of too few cells is refused with the count it needs", "[thin_plate]") {
  // It said "has 2 cells ...; needs at least 2, and more than its ghost layers (2)".
  PlateEdges edges;
  REQUIRE_THROWS_WITH(make_plate_cloud(square(1.0), 0.5, edges, 2),
                      Catch::Contains("the plate has 2 cells along x; a thin plate needs at least 3 (2, and more than "
                                      "its 2 ghost layers)"));
  REQUIRE_THROWS_WITH(make_plate_cloud(square(1.0), 1.0, edges, 1), Catch::Contains("needs at least 2"));
  REQUIRE_NOTHROW(make_plate_cloud(square(1.0), 1.0 / 3.0, edges, 2));
}

TEST_CASE("a plate built with an option out of range is refused naming the option", "[models][plate]") {
  // A library caller's thickness of 0 made D0 = 0 and a singular stiffness named nowhere.
  const auto refused = [](const ThinPlateOptions& o, const std::string& named) {
    PlateCloud cloud = make_plate_cloud(square(1.0), 0.125, {ss, ss, ss, ss}, 2);
    const Families f = radius_families(cloud.cloud, 2.015 * 0.125);
    try {
      ThinPlateModel m(std::move(cloud), f, o);
      FAIL("accepted " << named);
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find("ThinPlateOptions::" + named) != std::string::npos);
    }
  };
  ThinPlateOptions o = steel(0.5);
  o.thickness = 0.0;
  refused(o, "thickness");
  o = steel(0.5), o.nu = 0.5;
  refused(o, "nu");
  o = steel(0.5), o.E = std::nan("");
  refused(o, "E");
  o = steel(0.5), o.density = -1.0;
  refused(o, "density");
  o = steel(0.5), o.stabilization = -0.1;
  refused(o, "stabilization");
}

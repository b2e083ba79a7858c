// Body-fitted particles from gmsh meshes (tests/data/*.geo made the committed .msh files):
// the particles' volumes fill the body, the boundary facets close it exactly (the discrete
// divergence theorem the consistent formulation rests on), and the consistent formulation
// passes the uniform-stress patch test on unstructured meshes with rollers at the faces of
// two groups and tractions on the others.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "../support/direct_solve.hpp"
#include "perinom/core/error.hpp"
#include "perinom/geometry/mesh_body.hpp"
#include "perinom/scene/problem.hpp"

using namespace perinom;

namespace {

std::string data(const std::string& file) { return std::string(PERINOM_SOURCE_DIR) + "/tests/data/" + file; }

double total_volume(const Body& b) {
  double v = 0.0;
  for (const double x : b.cloud.volume) v += x;
  return v;
}

}  // namespace

TEST_CASE("a mesh's particles fill the body and its facets close it, in 2-D and 3-D", "[geometry][mesh]") {
  struct Case {
    const char* file;
    int dim;
    double volume;     ///< the body's volume (m^3; 2-D: area times the thickness 0.002)
    double tolerance;  ///< relative; curved bodies are meshed by chords, so only near
  };
  const double a = 0.01, b = 0.02;
  const Case cases[] = {{"square_tri.msh", 2, 0.016 * 0.016 * 0.002, 1e-13},
                        {"annulus_mixed.msh", 2, M_PI / 4 * (b * b - a * a) * 0.002, 1e-2},
                        {"cube_tet.msh", 3, 0.006 * 0.006 * 0.006, 1e-13},
                        {"box_hex.msh", 3, 0.010 * 0.008 * 0.006, 1e-3},
                        {"box_tet.msh", 3, 0.010 * 0.008 * 0.006 - M_PI * 0.002 * 0.002 * 0.006, 3e-2}};
  for (const Case& c : cases) {
    const Body body = mesh_body(read_gmsh(data(c.file)), c.dim, 0.002);
    const double defect = divergence_theorem_defect(body.facets, body.cloud);
    const double volume = total_volume(body);
    WARN(c.file << ": " << body.cloud.size() << " particles, " << body.facets.size() << " facets, volume "
                << volume << " against " << c.volume << ", divergence theorem defect " << defect);
    CHECK(std::abs(volume - c.volume) <= c.tolerance * c.volume);
    CHECK(defect <= 1e-12);
    // Every facet belongs to a group of these meshes (they name their whole boundary).
    std::size_t grouped = 0;
    for (const auto& g : body.groups) grouped += g.facets.size();
    CHECK(grouped == body.facets.size());
  }
}

TEST_CASE("a 3-D mesh in a 2-D scene is named as not planar, before any element is read", "[geometry][mesh]") {
  // It met "element 1 of the file's element list ... has zero area" first: the planarity
  // check ran after the elements.
  try {
    mesh_body(read_gmsh(data("cube_tet.msh")), 2, 0.002);
    FAIL("a 3-D mesh was taken for a 2-D body");
  } catch (const InputError& e) {
    CHECK_THAT(e.what(), Catch::StartsWith("a 2-D scene needs a mesh in a plane z = const"));
  }
}

TEST_CASE("a mesh's facets are its boundary faces, with exact areas and outward normals", "[geometry][mesh]") {
  // The 16 mm square: each side's facets add up to 16 mm (times the thickness), with the
  // side's normal, and the 2-D elements' areas are exact.
  const Body body = mesh_body(read_gmsh(data("square_tri.msh")), 2, 0.002);
  const double L = 0.016;
  const std::map<std::string, std::array<double, 2>> normals = {
      {"left", {-1, 0}}, {"right", {1, 0}}, {"bottom", {0, -1}}, {"top", {0, 1}}};
  REQUIRE(body.groups.size() == 4);
  for (const auto& g : body.groups) {
    double length = 0.0;
    for (const std::size_t k : g.facets) {
      length += body.facets.area[k] / 0.002;
      CHECK(std::abs(body.facets.normal[2 * k] - normals.at(g.name)[0]) <= 1e-14);
      CHECK(std::abs(body.facets.normal[2 * k + 1] - normals.at(g.name)[1]) <= 1e-14);
    }
    CHECK(std::abs(length - L) <= 1e-15);
  }
  CHECK(body.elements == body.cloud.size());
  CHECK(body.mean_size == Approx(std::sqrt(L * L / body.cloud.size())).epsilon(1e-12));
}

namespace {

const double traction[3] = {1.0e5, -2.5e5, 0.7e5};

/// The patch on a mesh: rollers at the faces of the min groups, tractions on the max ones.
std::string patch_scene(const std::string& mesh, int dim, const char* lo[3], const char* hi[3]) {
  std::ostringstream s;
  s << "name: patch\ndimension: " << dim << "\ngeometry: {mesh: " << data(mesh) << ", thickness: 0.002}\n"
    << "discretization: {dx: 0.001, horizon: {ratio: 3.015}}\n"
    << "material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000" << (dim == 2 ? ", plane: strain" : "")
    << "}\nboundary:\n";
  const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < dim; ++a) {
    s << "  - {region: {group: " << lo[a] << "}, fix: [" << axes[a] << "], at: face}\n"
      << "  - {region: {group: " << hi[a] << "}, traction: [";
    for (int b = 0; b < dim; ++b) s << (b ? ", " : "") << (a == b ? traction[a] : 0.0);
    s << "]}\n";
  }
  return s.str();
}

/// Largest errors of the displacement and the stress against the uniform state, relative.
std::pair<double, double> patch_errors(const std::string& scene, int dim) {
  Problem p = build_problem(parse_scene(scene, "patch"));
  const LinearElastic& mat = p.as<CorrespondenceModel>().material();
  Eigen::MatrixXd A = Eigen::MatrixXd::Constant(dim, dim, mat.lambda());
  A.diagonal().array() += 2.0 * mat.mu();
  Eigen::VectorXd sigma(dim);
  for (int a = 0; a < dim; ++a) sigma[a] = traction[a];
  const Eigen::VectorXd eps = A.lu().solve(sigma);
  std::vector<double> exact(p.as<CorrespondenceModel>().dofs());
  for (std::size_t i = 0; i < p.cloud.size(); ++i)
    for (int a = 0; a < dim; ++a) exact[i * dim + a] = eps[a] * p.cloud.x[i * dim + a];
  const auto u = test::direct_solve(p.as<CorrespondenceModel>(), p.loading);
  double du = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) du = std::max(du, std::abs(u[k] - exact[k])), scale = std::max(scale, std::abs(exact[k]));
  std::vector<double> s3;
  p.as<CorrespondenceModel>().stress3(u.data(), s3);
  double ds = 0.0;
  for (std::size_t i = 0; i < p.cloud.size(); ++i)
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b) ds = std::max(ds, std::abs(s3[i * 9 + a * 3 + b] - (a == b ? traction[a] : 0.0)));
  return {du / scale, ds / std::abs(traction[1])};
}

}  // namespace

TEST_CASE("the consistent formulation passes the patch test on unstructured meshes", "[models][patch][mesh]") {
  const char* lo2[3] = {"left", "bottom", ""};
  const char* hi2[3] = {"right", "top", ""};
  const auto e2 = patch_errors(patch_scene("square_tri.msh", 2, lo2, hi2), 2);
  WARN("triangles of a square, consistent: displacement " << e2.first << ", stress " << e2.second);
  CHECK(e2.first <= 1e-10);
  CHECK(e2.second <= 1e-10);
  const char* lo3[3] = {"xmin", "ymin", "zmin"};
  const char* hi3[3] = {"xmax", "ymax", "zmax"};
  const auto e3 = patch_errors(patch_scene("cube_tet.msh", 3, lo3, hi3), 3);
  WARN("tetrahedra of a cube, consistent: displacement " << e3.first << ", stress " << e3.second);
  CHECK(e3.first <= 1e-10);
  CHECK(e3.second <= 1e-10);
}

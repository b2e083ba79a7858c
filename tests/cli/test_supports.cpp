// Supports as a user writes them (issue 14, item 5): point regions that survive refinement,
// constraints: rigid_body for a free body under balanced loads, and the reaction of every
// support with the equilibrium error, in summary.json and history.csv. Each case runs the
// real binary on a small scene.
#include <catch2/catch.hpp>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include "../support/slurp.hpp"

namespace fs = std::filesystem;

namespace {

using test_support::json_number;
using test_support::slurp;

struct Run {
  int exit_code = -1;
  std::string out, err, summary, history;
};

/// Writes `scene` into a fresh folder named `name` and runs `perinom run scene.yaml --out out ARGS`.
Run run(const std::string& name, const std::string& scene, const std::string& args = "") {
  const fs::path d = fs::temp_directory_path() / ("perinom_supports_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "scene.yaml") << scene;
  const std::string cmd = "cd '" + d.string() + "' && '" PERINOM_EXE "' run scene.yaml --out out " + args +
                          " >out.txt 2>err.txt";
  const int status = std::system(cmd.c_str());
  Run r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(d / "out.txt");
  r.err = slurp(d / "err.txt");
  r.summary = slurp(d / "out" / "summary.json");
  r.history = slurp(d / "out" / "history.csv");
  fs::remove_all(d);
  return r;
}

/// The numbers of the JSON array that follows "key": in text (empty if absent).
std::vector<double> json_array(const std::string& text, const std::string& key) {
  std::vector<double> out;
  auto at = text.find("\"" + key + "\": [");
  if (at == std::string::npos) return out;
  at = text.find('[', at) + 1;
  const auto end = text.find(']', at);
  std::stringstream s(text.substr(at, end - at));
  for (std::string item; std::getline(s, item, ',');) out.push_back(std::stod(item));
  return out;
}

/// A 20 x 10 mm plane-stress plate with no support, pulled by 1 MPa on the left and the right.
const std::string free_plate = R"(name: free_plate
dimension: 2
geometry: {box: {min: [0.0, 0.0], max: [0.02, 0.01]}}
discretization: {dx: 0.001, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0, plane: stress}
constraints: rigid_body
boundary:
  - {region: left, traction: [-1.0e6, 0.0]}
  - {region: right, traction: [1.0e6, 0.0]}
solver: {type: newton}
probes:
  - {name: sxx_center, point: [0.01, 0.005], field: stress, component: xx}
  - {name: sxx_corner, point: [0.0, 0.0], field: stress, component: xx}
  - {name: syy_center, point: [0.01, 0.005], field: stress, component: yy}
  - {name: sxy_corner, point: [0.02, 0.01], field: stress, component: xy}
)";

std::string with(std::string scene, const std::string& from, const std::string& to) {
  const auto at = scene.find(from);
  REQUIRE(at != std::string::npos);
  return scene.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("a point region pins the particle nearest its point whatever the spacing", "[cli][supports]") {
  // Rollers on the bottom and a pin at the corner (0, 0) in x: the corner holds still and the
  // plate spreads to the right under the pressure, at both spacings.
  const std::string scene = R"(name: pinned
dimension: 2
geometry: {box: {min: [0.0, 0.0], max: [0.01, 0.01]}}
discretization: {dx: 0.001, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0}
boundary:
  - {region: bottom, fix: [y], at: face}
  - {region: {point: [0.0, 0.0]}, fix: [x]}
  - {region: top, pressure: 1.0e6}
solver: {type: newton}
probes:
  - {name: corner_ux, point: [0.0, 0.0], component: x}
  - {name: far_corner_ux, point: [0.01, 0.0], component: x}
)";
  for (const char* dx : {"0.001", "0.0005"}) {
    INFO("dx = " << dx);
    const Run r = run("point", scene, std::string("--set discretization.dx=") + dx);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(json_number(r.summary, "corner_ux") == 0.0);
    CHECK(json_number(r.summary, "far_corner_ux") > 1e-7);
    // The pin holds the plate in x alone: its reaction is the x force the supports need, zero
    // here by symmetry of the loads up to the solve.
    const auto pin = json_array(r.summary, "boundary.1");
    REQUIRE(pin.size() == 2);
    CHECK(std::abs(pin[0]) < 1e-6 * 1e4);
    CHECK(pin[1] == 0.0);
  }
}

TEST_CASE("a point region with a wrong length or non-numbers is bad input naming the key", "[cli][supports]") {
  const std::string scene = with(free_plate, "constraints: rigid_body\n", "");
  for (const char* bad : {"[0.0]", "[0.0, a]", "[0.0, 0.0, 0.0]"}) {
    INFO(bad);
    const Run r = run("bad_point", with(scene, "{region: left, traction", std::string("{region: {point: ") + bad + "}, traction"));
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("boundary[0].region.point: must be a list of 2 numbers") != std::string::npos);
  }
  const Run both = run("both", with(scene, "{region: left, traction", "{region: {point: [0, 0], box: {min: [0, 0], max: [1, 1]}}, traction"));
  CHECK(both.exit_code == 2);
  CHECK(both.err.find("boundary[0].region: give exactly one of box, point or group") != std::string::npos);
}

TEST_CASE("constraints rigid_body holds a free plate under balanced tractions at the uniform stress", "[cli][supports]") {
  for (const char* solver : {"newton", "adr"}) {
    INFO(solver);
    const Run r = run("rigid", free_plate,
                      std::string("--set solver.type=") + solver + " --set solver.tolerance=1e-10 --set solver.displacement_tolerance=1e-10");
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    const double tol = std::string(solver) == "newton" ? 1e-9 : 1e-6;
    CHECK(json_number(r.summary, "sxx_center") == Approx(1e6).epsilon(tol));
    CHECK(json_number(r.summary, "sxx_corner") == Approx(1e6).epsilon(tol));
    CHECK(std::abs(json_number(r.summary, "syy_center")) < tol * 1e6);
    CHECK(std::abs(json_number(r.summary, "sxy_corner")) < tol * 1e6);
    // Which particles hold which dofs, on stdout and in the summary: 3 dofs in 2-D.
    CHECK(r.out.find("constraints rigid_body: pinned particle") != std::string::npos);
    CHECK(r.summary.find("\"rigid_body\": [") != std::string::npos);
    CHECK(r.out.find(") in x, y; particle") != std::string::npos);
    CHECK(r.out.find(") in y\n") != std::string::npos);
    // The pins carry nothing: the loads balance.
    const auto pins = json_array(r.summary.substr(r.summary.find("\"reactions\"")), "rigid_body");
    REQUIRE(pins.size() == 2);
    CHECK(std::hypot(pins[0], pins[1]) < tol * 2e4);
  }
}

TEST_CASE("a free plate without constraints is singular, and rigid_body refuses unbalanced loads and supports",
          "[cli][supports]") {
  const Run none = run("none", free_plate, "--set constraints=none");
  CHECK(none.exit_code == 2);
  CHECK(none.err.find("singular") != std::string::npos);
  // The warning before the solve names the motions: a free plane body has three.
  CHECK(none.out.find("perinom: warning: boundary: the supports leave the body 3 rigid motion(s) free") != std::string::npos);
  const Run force = run("unbalanced_force", free_plate, "--set boundary.1.traction=[1.0e6,0.0001e6]");
  CHECK(force.exit_code == 2);
  CHECK(force.err.find("scene.yaml: constraints: the external loads are not balanced") != std::string::npos);
  CHECK(force.summary.find("\"status\": \"error\"") != std::string::npos);  // no result: the error
  CHECK(force.summary.find("\"reactions\"") == std::string::npos);
  // Equal and opposite shear on left and right: no net force, but a couple.
  const Run moment = run("unbalanced_moment", free_plate,
                         "--set boundary.0.traction=[0.0,-1.0e6] --set boundary.1.traction=[0.0,1.0e6]");
  CHECK(moment.exit_code == 2);
  CHECK(moment.err.find("constraints: the external loads are not balanced") != std::string::npos);
  CHECK(moment.err.find("moment 200 N m") != std::string::npos);
  const Run held = run("held", with(free_plate, "{region: left, traction: [-1.0e6, 0.0]}", "{region: left, fix: [x]}"));
  CHECK(held.exit_code == 2);
  CHECK(held.err.find("constraints: rigid_body is for a body held by no support, but boundary.0 fixes") != std::string::npos);
  const Run typo = run("typo", free_plate, "--set constraints=rigid");
  CHECK(typo.exit_code == 2);
  CHECK(typo.err.find("constraints: must be none or rigid_body") != std::string::npos);
}

TEST_CASE("a pure shear balanced at the faces is refused under layer loads with the reason, and runs at the faces", "[cli][supports]") {
  // Classical puts the shear tractions half a spacing inside the faces: their moment is
  // tau dx (L - h) = 1e6 * 0.001 * 0.01 * 1 m = 10 N m. The message blamed the loads alone.
  const std::string shear = with(free_plate, "  - {region: left, traction: [-1.0e6, 0.0]}\n  - {region: right, traction: [1.0e6, 0.0]}\n",
                                 "  - {region: left, traction: [0.0, -1.0e6]}\n  - {region: right, traction: [0.0, 1.0e6]}\n"
                                 "  - {region: bottom, traction: [-1.0e6, 0.0]}\n  - {region: top, traction: [1.0e6, 0.0]}\n");
  const Run layer = run("shear_layer", shear, "--set model.formulation=classical");
  CHECK(layer.exit_code == 2);
  CHECK(layer.err.find("moment 10 N m") != std::string::npos);
  CHECK(layer.err.find("this formulation applies tractions at the outer layer's particles (half a spacing inside the "
                       "faces), whose moments need not cancel") != std::string::npos);
  const Run faces = run("shear_faces", shear);
  INFO(faces.out << faces.err);
  CHECK(faces.exit_code == 0);
}

TEST_CASE("constraints rigid_body pins 6 dofs of a free 3-D bar in tension", "[cli][supports]") {
  const std::string bar = R"(name: free_bar
dimension: 3
geometry: {box: {min: [0.0, 0.0, 0.0], max: [0.012, 0.006, 0.004]}}
discretization: {dx: 0.001, horizon: {ratio: 2.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0}
constraints: rigid_body
boundary:
  - {region: left, traction: [-1.0e6, 0.0, 0.0]}
  - {region: right, traction: [1.0e6, 0.0, 0.0]}
solver: {type: newton}
probes:
  - {name: sxx, point: [0.0, 0.006, 0.004], field: stress, component: xx}
  - {name: szz, point: [0.006, 0.003, 0.002], field: stress, component: zz}
)";
  const Run r = run("bar", bar);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(json_number(r.summary, "sxx") == Approx(1e6).epsilon(1e-9));
  CHECK(std::abs(json_number(r.summary, "szz")) < 1e-3);
  // A in x, y, z; B across the long axis x (y, z); C along z at the far end of y: 6 dofs.
  CHECK(r.out.find("in x, y, z; particle") != std::string::npos);
  CHECK(r.out.find(") in y, z; particle") != std::string::npos);
  CHECK(r.out.find(") in z\n") != std::string::npos);
}

TEST_CASE("reactions balance the applied load on the uniaxial compression example", "[cli][supports]") {
  const std::string scene = slurp(PERINOM_SOURCE_DIR "/examples/uniaxial_compression.yaml");
  for (const char* solver : {"newton", "adr"}) {
    INFO(solver);
    const Run r = run("uniaxial", scene, std::string("--set model.formulation=consistent --set solver.type=") + solver);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    // 200 kPa on the 36 mm top (thickness 1 m) pushes down with 7200 N; the bottom pushes back.
    const auto bottom = json_array(r.summary, "boundary.0");
    REQUIRE(bottom.size() == 2);
    const double tol = std::string(solver) == "newton" ? 1e-10 : 1e-6;
    CHECK(bottom[1] == Approx(200.0e3 * 0.036).epsilon(tol));
    CHECK(std::abs(bottom[0]) < tol * 7200.0);
    const auto applied = json_array(r.summary, "applied");
    REQUIRE(applied.size() == 2);
    CHECK(applied[1] == Approx(-7200.0).epsilon(1e-12));
    CHECK(json_number(r.summary, "error") < tol);
    CHECK(r.out.find("perinom: equilibrium: applied loads") != std::string::npos);
    // history.csv: the reaction columns, the last row's value that of the final state.
    CHECK(r.history.find(",boundary.0.Rx,boundary.0.Ry\n") != std::string::npos);
  }
}

TEST_CASE("a body in pieces is checked piece by piece, and rigid_body refuses it", "[cli][supports]") {
  // Two pieces, the second held in y only: the whole body's check counted the first piece's
  // supports, said nothing, and ADR ran its 200,000 iterations; rigid_body's three pins held
  // one piece and Newton blamed a missing boundary condition.
  const std::string cut = "precracks:\n  - {from: [-0.001, 0.0051], to: [0.021, 0.0051]}\n";
  const std::string held = with(with(with(free_plate, "constraints: rigid_body\n", "model: {formulation: classical}\n" + cut),
                                     "  - {region: left, traction: [-1.0e6, 0.0]}\n",
                                     "  - {region: bottom, fix: [x, y]}\n  - {region: top, fix: [y]}\n"),
                                "  - {region: right, traction: [1.0e6, 0.0]}\n", "  - {region: right, traction: [0.0, 1.0e5]}\n");
  const fs::path d = fs::temp_directory_path() / "perinom_supports_pieces";
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "scene.yaml") << held;
  const std::string cmd = "cd '" + d.string() + "' && '" PERINOM_EXE "' check scene.yaml >out.txt 2>err.txt";
  CHECK(std::system(cmd.c_str()) == 0);
  const std::string out = slurp(d / "out.txt");
  INFO(out);
  CHECK(out.find("the body is in 2 pieces that no bond joins, and the supports leave the piece of 100 particle(s) "
                 "around (0.01, 0.0075) m 1 rigid motion(s) free: it can move along (1, 0)") != std::string::npos);
  fs::remove_all(d);
  const Run r = run("pieces_rigid", with(free_plate, "constraints: rigid_body\n",
                                         "constraints: rigid_body\nmodel: {formulation: classical}\n" + cut));
  INFO(r.out << r.err);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("constraints: rigid_body holds one body, and this one is in 2 pieces that no bond joins") !=
        std::string::npos);
}

TEST_CASE("the clamped face of a 3-D cantilever reacts to the tip shear", "[cli][supports]") {
  // L = 100 mm, 10 x 10 mm, 1 MPa of shear in -z on the tip face: 100 N down, so the clamp
  // pushes up with 100 N (reaction = -applied load) and holds the moment.
  const std::string scene = R"(name: cantilever
dimension: 3
geometry: {box: {min: [0.0, 0.0, 0.0], max: [0.1, 0.01, 0.01]}}
discretization: {dx: 0.0025, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 200.0e9, nu: 0.3, density: 7850.0}
boundary:
  - {region: left, fix: [x, y, z], at: face}
  - {region: right, traction: [0.0, 0.0, -1.0e6]}
solver: {type: newton}
)";
  const Run r = run("cantilever", scene);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const auto clamp = json_array(r.summary, "boundary.0");
  REQUIRE(clamp.size() == 3);
  CHECK(clamp[2] == Approx(100.0).epsilon(1e-9));
  CHECK(std::abs(clamp[0]) < 1e-7);
  CHECK(std::abs(clamp[1]) < 1e-7);
  CHECK(json_number(r.summary, "error") < 1e-9);
  const auto rows = r.history.substr(r.history.find('\n') + 1);
  CHECK(r.history.rfind("load_step,load_factor,newton_iterations,residual,boundary.0.Rx,boundary.0.Ry,boundary.0.Rz\n", 0) == 0);
  CHECK(std::stod(rows.substr(rows.rfind(',') + 1)) == Approx(100.0).epsilon(1e-9));
}

// What `perinom run` leaves behind: VTK files that VTK's own reader accepts with the right
// fields and sizes, and, when a solve blows up, exit code 3 with the last good state.
#include <catch2/catch.hpp>
#include <sys/wait.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include "../support/slurp.hpp"

namespace fs = std::filesystem;

namespace {

const char* scene = R"(name: plate
dimension: 2
geometry: {box: {min: [0.0, 0.0], max: [0.012, 0.008]}}
discretization: {dx: 0.001, horizon: {ratio: 3.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0}
boundary:
  - {region: bottom, fix: [x, y]}
  - {region: top, pressure: 1.0e6}
solver: {type: verlet, steps: 400, history_every: 10}
)";

int run_perinom(const fs::path& dir, const std::string& args) {
  const std::string cmd = "cd '" + dir.string() + "' && '" PERINOM_EXE "' " + args + " >out.txt 2>err.txt";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

using test_support::json_number;
using test_support::slurp;

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("perinom_run_output_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "scene.yaml") << scene;
  return d;
}

}  // namespace

TEST_CASE("run output reads back with VTK's XML reader, with the right fields and sizes", "[cli][io]") {
  const fs::path d = scratch("vtk");
  REQUIRE(run_perinom(d, "run scene.yaml --out out --set output.vtk_every=100") == 0);
  const std::string pvd = slurp(d / "out" / "plate.pvd");
  CHECK(pvd.find("plate_000003.vtu") != std::string::npos);  // 4 snapshots (0-3) at steps 100..400
  CHECK_FALSE(fs::exists(d / "out" / "plate_000004.vtu"));   // and no duplicate final one
  auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  reader->SetFileName((d / "out" / "plate_000003.vtu").c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  REQUIRE(grid != nullptr);
  CHECK(grid->GetNumberOfPoints() == 12 * 8);
  CHECK(grid->GetNumberOfCells() == 12 * 8);
  vtkPointData* pd = grid->GetPointData();
  const std::pair<const char*, int> fields[] = {{"displacement", 3}, {"stress", 9}, {"von_mises", 1}, {"volume", 1}};
  for (const auto& [name, comps] : fields) {
    INFO(name);
    vtkDataArray* a = pd->GetArray(name);
    REQUIRE(a != nullptr);
    CHECK(a->GetNumberOfComponents() == comps);
    CHECK(a->GetNumberOfTuples() == 12 * 8);
  }
  // The plate is pushed down: some particle moved down, none has a NaN.
  double min_uy = 0.0;
  vtkDataArray* u = pd->GetArray("displacement");
  for (vtkIdType i = 0; i < u->GetNumberOfTuples(); ++i) {
    REQUIRE(std::isfinite(u->GetComponent(i, 1)));
    min_uy = std::min(min_uy, u->GetComponent(i, 1));
  }
  CHECK(min_uy < 0.0);
  CHECK(pd->GetArray("volume")->GetComponent(0, 0) == Approx(1e-6));
}

TEST_CASE("a solve that blows up exits 3 and writes its last good state and summary", "[cli]") {
  const fs::path d = scratch("nan");
  // Fifty times the stable step: Verlet diverges to Inf within a few hundred steps. The
  // energy-balance guard would stop it sooner; it is off so that the NaN guard is tested.
  REQUIRE(run_perinom(d, "run scene.yaml --out out --set solver.dt=1e-5 --set solver.steps=5000 "
                         "--set solver.energy_check=false") == 3);
  const std::string err = slurp(d / "err.txt");
  CHECK(err.find("solve failed") != std::string::npos);
  CHECK(err.find("NaN or Inf") != std::string::npos);
  const std::string summary = slurp(d / "out" / "summary.json");
  CHECK(summary.find("\"converged\": false") != std::string::npos);
  CHECK(summary.find("\"error\"") != std::string::npos);
  CHECK(fs::exists(d / "out" / "history.csv"));
  auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  reader->SetFileName((d / "out" / "plate_000000.vtu").c_str());
  reader->Update();
  vtkDataArray* u = reader->GetOutput()->GetPointData()->GetArray("displacement");
  REQUIRE(u != nullptr);
  for (vtkIdType i = 0; i < u->GetNumberOfTuples(); ++i)
    for (int c = 0; c < 3; ++c) REQUIRE(std::isfinite(u->GetComponent(i, c)));
}

namespace {

/// Whether a CSV or JSON text holds a non-finite number: a word nan, inf or infinity (any
/// case, any sign) outside double-quoted strings (a JSON message may say "NaN or Inf").
bool has_nonfinite_text(const std::string& text) {
  bool quoted = false;
  std::string word;
  for (const char c : text + "\n") {
    if (c == '"') quoted = !quoted;
    if (!quoted && std::isalpha(static_cast<unsigned char>(c))) {
      word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      continue;
    }
    if (word == "nan" || word == "inf" || word == "infinity") return true;
    word.clear();
  }
  return false;
}

}  // namespace

TEST_CASE("Verlet at three times its stable step: exit 3, no NaN or Inf in any file, the step in the summary", "[cli]") {
  const fs::path d = scratch("diverged");
  REQUIRE(run_perinom(d, "run scene.yaml --out probe --set solver.steps=1") == 0);
  const double stable = json_number(slurp(d / "probe" / "summary.json"), "stable_time_step");
  std::ostringstream dt;
  dt.precision(17);
  dt << 3.0 * stable;
  // Snapshots (VTK and CSV) and history rows every 5 steps, up to the last one before the guard.
  // The energy balance would stop the run at its first row (step 5); this test is the NaN guard's.
  REQUIRE(run_perinom(d, "run scene.yaml --out out --set solver.dt=" + dt.str() +
                             " --set solver.steps=100000 --set solver.history_every=5 --set output.vtk_every=5 "
                             "--set output.csv=true --set solver.energy_check=false") == 3);
  const fs::path out = d / "out";
  const std::string summary = slurp(out / "summary.json");
  INFO(summary);
  CHECK(summary.find("\"status\": \"diverged\"") != std::string::npos);
  const double failed = json_number(summary, "diverged_at"), last = json_number(summary, "last_good");
  CHECK(failed > 10);
  CHECK(last == failed - 1);
  CHECK(json_number(summary, "end_time") == Approx(last * 3.0 * stable).epsilon(1e-9));
  int vtu = 0;
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    INFO(name);
    CHECK(e.path().extension() != ".tmp");
    if (e.path().extension() != ".vtu") {
      CHECK_FALSE(has_nonfinite_text(slurp(e.path())));
      continue;
    }
    ++vtu;
    auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    reader->SetFileName(e.path().c_str());
    reader->Update();
    vtkPointData* pd = reader->GetOutput()->GetPointData();
    REQUIRE(pd->GetNumberOfArrays() > 0);
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a) {
      vtkDataArray* arr = pd->GetArray(a);
      for (vtkIdType i = 0; i < arr->GetNumberOfTuples(); ++i)
        for (int c = 0; c < arr->GetNumberOfComponents(); ++c) REQUIRE(std::isfinite(arr->GetComponent(i, c)));
    }
  }
  CHECK(vtu > 2);
  // The history's last row is at or before the last good step.
  const std::string history = slurp(out / "history.csv");
  const auto last_line = history.substr(history.rfind('\n', history.size() - 2) + 1);
  CHECK(std::stod(last_line) <= last);
}

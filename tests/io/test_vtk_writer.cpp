#include <catch2/catch.hpp>

#include <vtkCellTypes.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <sys/resource.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "perinom/core/error.hpp"
#include "perinom/io/csv_writer.hpp"
#include "perinom/io/json_writer.hpp"
#include "perinom/io/vtk_writer.hpp"

namespace fs = std::filesystem;
using perinom::io::PointField;

namespace {

/// A fresh directory under the system temp folder, removed with its contents at scope end.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "perinom_io_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp " + pattern);
    path = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool any_tmp_file(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".tmp") return true;
  return false;
}

/// Writes a cloud of n points with a displacement (dim), a stress (9) and a damage (1)
/// field, reads it back with VTK's own reader and checks every value.
void check_round_trip(int dim) {
  ScratchDir dir;
  const std::size_t n = 7;
  std::vector<double> x(n * dim), u(n * dim), stress(n * 9), damage(n);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.1 * i + 1.0 / 3.0;
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = -1e-7 * i;
  for (std::size_t i = 0; i < stress.size(); ++i) stress[i] = 1e6 * std::sin(i);
  for (std::size_t i = 0; i < n; ++i) damage[i] = i / double(n);
  const std::string path = dir / "cloud.vtu";
  perinom::io::write_vtu(path, dim, n, x.data(),
                         {{"displacement", dim, u.data()},
                          {"stress", 9, stress.data()},
                          {"damage", 1, damage.data()}});
  REQUIRE(fs::exists(path));
  REQUIRE_FALSE(any_tmp_file(dir.path));

  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  REQUIRE(grid->GetNumberOfPoints() == vtkIdType(n));
  REQUIRE(grid->GetNumberOfCells() == vtkIdType(n));
  for (vtkIdType c = 0; c < vtkIdType(n); ++c) CHECK(grid->GetCellType(c) == VTK_VERTEX);
  for (std::size_t i = 0; i < n; ++i) {
    double p[3];
    grid->GetPoint(vtkIdType(i), p);
    for (int d = 0; d < 3; ++d) CHECK(p[d] == (d < dim ? x[i * dim + d] : 0.0));
  }

  vtkPointData* pd = grid->GetPointData();
  const std::vector<PointField> expected = {
      {"displacement", dim, u.data()}, {"stress", 9, stress.data()}, {"damage", 1, damage.data()}};
  for (const PointField& f : expected) {
    INFO("field " << f.name);
    vtkDataArray* array = pd->GetArray(f.name.c_str());
    REQUIRE(array != nullptr);
    REQUIRE(array->GetNumberOfComponents() == f.components);
    REQUIRE(array->GetNumberOfTuples() == vtkIdType(n));
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < f.components; ++c)
        CHECK(array->GetComponent(vtkIdType(i), c) == f.data[i * f.components + c]);
  }
  REQUIRE(pd->GetTensors() != nullptr);
  CHECK(std::string(pd->GetTensors()->GetName()) == "stress");
}

}  // namespace

TEST_CASE("a 2-D cloud written as .vtu reads back with z = 0 and every field", "[io]") {
  check_round_trip(2);
}

TEST_CASE("a 3-D cloud written as .vtu reads back with every field", "[io]") {
  check_round_trip(3);
}

TEST_CASE("a .pvd series lists its .vtu files with their times and leaves no .tmp", "[io]") {
  ScratchDir dir;
  const std::vector<double> x = {0, 0, 1, 0, 0, 1};
  const std::vector<double> u = {0.5, 0.25, -1, 2, 3, 4};
  perinom::io::PvdSeries series(dir.path.string(), "run");
  const std::vector<double> times = {0.0, 1.5e-6, 0.125};
  for (std::size_t k = 0; k < times.size(); ++k) {
    const std::string file = series.add(times[k], 2, 3, x.data(), {{"displacement", 2, u.data()}});
    CHECK(file == "run_00000" + std::to_string(k) + ".vtu");
    CHECK(fs::exists(dir / file));
  }
  series.write();
  REQUIRE(series.size() == 3);
  REQUIRE_FALSE(any_tmp_file(dir.path));

  const std::string xml = read_text(dir / "run.pvd");
  CHECK(xml.find("type=\"Collection\"") != std::string::npos);
  std::vector<std::string> files;
  std::vector<double> read_times;
  for (std::size_t at = xml.find("<DataSet"); at != std::string::npos;
       at = xml.find("<DataSet", at + 1)) {
    const std::size_t t = xml.find("timestep=\"", at) + 10;
    read_times.push_back(std::strtod(xml.c_str() + t, nullptr));
    const std::size_t f = xml.find("file=\"", at) + 6;
    files.push_back(xml.substr(f, xml.find('"', f) - f));
  }
  REQUIRE(files == std::vector<std::string>{"run_000000.vtu", "run_000001.vtu", "run_000002.vtu"});
  REQUIRE(read_times == times);
}

TEST_CASE("write_vtu into a missing or unwritable folder throws InputError naming the path",
          "[io]") {
  ScratchDir dir;
  std::ofstream(dir / "plain_file") << "not a folder";
  const std::vector<double> x = {0, 0, 1, 1};
  for (const std::string& path :
       {dir / "missing/cloud.vtu", dir / "plain_file/cloud.vtu"}) {
    INFO(path);
    bool thrown = false;
    try {
      perinom::io::write_vtu(path, 2, 2, x.data(), {});
    } catch (const perinom::InputError& e) {
      thrown = true;
      CHECK_THAT(e.what(), Catch::Contains(path));
    }
    CHECK(thrown);
  }
}

TEST_CASE("a write the file system refuses midway names the system reason, not a VTK code", "[io]") {
  // A full disk read "cannot write VTK file ...: VTK error code 28" (errno ENOSPC), after a
  // dozen lines of VTK's pipeline request on stderr. A file-size limit makes the same kind of
  // failure: the writer's write() fails with EFBIG (the SIGXFSZ it raises is ignored here).
  ScratchDir dir;
  const std::size_t n = 20000;  // about 0.5 MB of coordinates and a field: past the 4 KiB limit
  std::vector<double> x(2 * n), f(n);
  for (std::size_t i = 0; i < n; ++i) x[2 * i] = std::sin(double(i)), x[2 * i + 1] = std::cos(3.0 * i), f[i] = std::tan(i);
  rlimit before{};
  REQUIRE(getrlimit(RLIMIT_FSIZE, &before) == 0);
  const auto handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = before;
  small.rlim_cur = 4096;
  REQUIRE(setrlimit(RLIMIT_FSIZE, &small) == 0);
  std::string message;
  try {
    perinom::io::write_vtu(dir / "big.vtu", 2, n, x.data(), {{"f", 1, f.data()}});
  } catch (const perinom::InputError& e) {
    message = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, handler);
  INFO(message);
  CHECK_THAT(message, Catch::Contains("big.vtu"));
  CHECK_THAT(message, Catch::Contains(std::strerror(EFBIG)));
  CHECK_FALSE(std::filesystem::exists(dir / "big.vtu.tmp"));
}

TEST_CASE("CsvWriter writes full-precision rows that read back exactly", "[io]") {
  ScratchDir dir;
  const std::string path = dir / "history.csv";
  const std::vector<std::vector<double>> rows = {{0.0, 0.1, 1.0 / 3.0},
                                                 {1e-300, -2.5, 6.02214076e23}};
  {
    perinom::io::CsvWriter csv(path);
    csv.header({"time", "energy", "force, x"});
    for (const auto& r : rows) csv.row(r);
    CHECK_THROWS_AS(csv.row({1.0}), std::invalid_argument);
    CHECK_FALSE(fs::exists(path));  // still under .tmp until closed
    csv.close();
  }
  REQUIRE(fs::exists(path));
  REQUIRE_FALSE(any_tmp_file(dir.path));

  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  CHECK(line == "time,energy,\"force, x\"");
  for (const auto& r : rows) {
    REQUIRE(std::getline(in, line));
    std::stringstream ss(line);
    std::string cell;
    for (double expected : r) {
      REQUIRE(std::getline(ss, cell, ','));
      CHECK(std::strtod(cell.c_str(), nullptr) == expected);
    }
  }
  CHECK_FALSE(std::getline(in, line));
  CHECK_THROWS_AS(perinom::io::CsvWriter(dir / "missing/h.csv"), perinom::InputError);
}

TEST_CASE("a CsvWriter never closed (an exception cut it short) leaves neither the file nor its .tmp", "[io]") {
  ScratchDir dir;
  const std::string path = dir / "history.csv";
  {
    perinom::io::CsvWriter csv(path);
    csv.header({"a"});
    csv.row({1.0});
    REQUIRE(any_tmp_file(dir.path));
  }
  CHECK_FALSE(fs::exists(path));
  CHECK_FALSE(any_tmp_file(dir.path));
}

TEST_CASE("Json dumps nested objects and arrays, escapes strings, writes NaN as null", "[io]") {
  using perinom::io::Json;
  Json summary = Json::object();
  summary["case"] = "plate \"A\"\n\\";
  summary["particles"] = std::size_t{12345};
  summary["converged"] = true;
  summary["errors"]["l2"] = 0.1;
  summary["errors"]["max"] = std::numeric_limits<double>::quiet_NaN();
  summary["history"].push_back(1);
  summary["history"].push_back(-2.5);
  summary["history"].push_back(Json::object());
  summary["empty"] = Json::array();
  summary["nothing"] = Json();
  CHECK(summary.dump(-1) ==
        R"({"case":"plate \"A\"\n\\","particles":12345,"converged":true,)"
        R"("errors":{"l2":0.1,"max":null},"history":[1,-2.5,{}],"empty":[],"nothing":null})");
  CHECK(Json(std::string("\x01")).dump() == R"("\u0001")");
  CHECK(Json(1.0 / 3.0).dump() == "0.3333333333333333");
  CHECK(Json(-std::numeric_limits<double>::infinity()).dump() == "null");
  CHECK_THROWS_AS(Json(1).push_back(2), std::logic_error);

  Json small = Json::object();
  small["a"].push_back("x");
  CHECK(small.dump(2) == "{\n  \"a\": [\n    \"x\"\n  ]\n}");

  ScratchDir dir;
  perinom::io::write_json_file(dir / "summary.json", summary);
  CHECK(read_text(dir / "summary.json") == summary.dump() + "\n");
  REQUIRE_FALSE(any_tmp_file(dir.path));
}

#include "perinom/io/vtk_writer.hpp"

#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "perinom/core/error.hpp"

namespace perinom::io {
namespace {

namespace fs = std::filesystem;

void check_arguments(const std::string& path, int dim, std::size_t n, const double* x,
                     const std::vector<PointField>& fields) {
  const std::string where = "write_vtu('" + path + "'): ";
  if (dim != 2 && dim != 3)
    throw std::invalid_argument(where + "dim must be 2 or 3, got " + std::to_string(dim));
  if (n > 0 && x == nullptr) throw std::invalid_argument(where + "coordinates are null");
  std::set<std::string> seen;
  for (const PointField& f : fields) {
    if (f.name.empty()) throw std::invalid_argument(where + "a point field has no name");
    if (!seen.insert(f.name).second)
      throw std::invalid_argument(where + "point field '" + f.name + "' appears twice");
    if (f.components < 1)
      throw std::invalid_argument(where + "point field '" + f.name + "' has " +
                                  std::to_string(f.components) + " components");
    if (n > 0 && f.data == nullptr)
      throw std::invalid_argument(where + "point field '" + f.name + "' has no data");
  }
}

vtkNew<vtkUnstructuredGrid> make_grid(int dim, std::size_t n, const double* x,
                                      const std::vector<PointField>& fields) {
  const auto count = static_cast<vtkIdType>(n);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(count);
  double* xyz = vtkDoubleArray::SafeDownCast(points->GetData())->GetPointer(0);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) xyz[3 * i + d] = d < dim ? x[dim * i + d] : 0.0;

  // Vertex cells let every ParaView filter (glyphs, thresholds) see the points.
  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(count + 1);
  connectivity->SetNumberOfValues(count);
  for (vtkIdType i = 0; i < count; ++i) {
    offsets->SetValue(i, i);
    connectivity->SetValue(i, i);
  }
  offsets->SetValue(count, count);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);

  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(VTK_VERTEX, cells);

  static const char* const tensor_names[9] = {"XX", "XY", "XZ", "YX", "YY",
                                              "YZ", "ZX", "ZY", "ZZ"};
  vtkPointData* point_data = grid->GetPointData();
  bool have_vector = false;
  bool have_tensor = false;
  for (const PointField& f : fields) {
    vtkNew<vtkDoubleArray> array;
    array->SetName(f.name.c_str());
    array->SetNumberOfComponents(f.components);
    array->SetNumberOfTuples(count);
    std::copy_n(f.data, n * static_cast<std::size_t>(f.components), array->GetPointer(0));
    point_data->AddArray(array);
    // The first 3- and 9-component arrays become the active attributes, which is what
    // the .vtu header records and what makes ParaView treat a 9-array as a tensor.
    if (f.components == 3 && !have_vector) {
      point_data->SetActiveVectors(f.name.c_str());
      have_vector = true;
    } else if (f.components == 9) {
      for (int c = 0; c < 9; ++c) array->SetComponentName(c, tensor_names[c]);
      if (!have_tensor) point_data->SetActiveTensors(f.name.c_str());
      have_tensor = true;
    }
  }
  return grid;
}

void publish(const fs::path& tmp, const fs::path& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw InputError("cannot rename '" + tmp.string() + "' to '" + path.string() +
                     "': " + ec.message());
  }
}

std::string xml_attribute(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

// vtkErrorCode::GetStringFromErrorCode lives in VTK::CommonMisc; naming the few codes
// the XML writer sets keeps the link line at CommonCore, CommonDataModel and IOXML.
std::string describe_vtk_error(unsigned long code) {
  switch (code) {
    case vtkErrorCode::CannotOpenFileError: return "VTK cannot open the file";
    case vtkErrorCode::OutOfDiskSpaceError: return "out of disk space";
    case vtkErrorCode::NoError: return "the VTK writer reported failure";
    default:
      // Below VTK's own codes (20000 on) the writer keeps errno: a full disk read "VTK error
      // code 28".
      if (code > 0 && code < vtkErrorCode::FirstVTKErrorCode) return std::strerror(static_cast<int>(code));
      return "VTK error code " + std::to_string(code);
  }
}

std::string shortest(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

}  // namespace

void write_vtu(const std::string& path, int dim, std::size_t n, const double* x,
               const std::vector<PointField>& fields) {
  check_arguments(path, dim, n, x, fields);
  const std::string tmp = path + ".tmp";
  {
    // Opening the file ourselves first turns a missing or read-only folder into one
    // clear error, instead of VTK's generic message on stderr.
    std::ofstream probe(tmp, std::ios::binary | std::ios::trunc);
    if (!probe)
      throw InputError("cannot write VTK file '" + path + "': opening '" + tmp +
                       "' failed: " + std::strerror(errno));
  }
  vtkNew<vtkUnstructuredGrid> grid = make_grid(dim, n, x, fields);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(tmp.c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  // 64-bit block headers: a large 3-D cloud passes 4 GiB of uncompressed data.
  writer->SetHeaderTypeToUInt64();
  // VTK's own account of a failed write (a dozen coloured lines of its pipeline's request on
  // stderr) is left out: the error below names the file and the reason.
  const int display = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOff();
  const int ok = writer->Write();
  vtkObject::SetGlobalWarningDisplay(display);
  const unsigned long code = writer->GetErrorCode();
  if (ok != 1 || code != vtkErrorCode::NoError) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw InputError("cannot write VTK file '" + path + "': " +
                     describe_vtk_error(code));
  }
  publish(tmp, path);
}

namespace {

/// An XML text to `path`, through path.tmp and a rename; `what` names it in errors.
void write_xml(const fs::path& path, const std::string& text, const char* what) {
  const fs::path tmp = fs::path(path.string() + ".tmp");
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw InputError(std::string("cannot write ") + what + " '" + path.string() + "': opening '" + tmp.string() +
                       "' failed: " + std::strerror(errno));
    out << text;
    out.close();
    if (!out) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw InputError(std::string("cannot write ") + what + " '" + path.string() + "': write failed");
    }
  }
  publish(tmp, path);
}

}  // namespace

PvdSeries::PvdSeries(std::string directory, std::string name)
    : directory_(std::move(directory)), name_(std::move(name)) {}

std::string PvdSeries::add(double time, int dim, std::size_t n, const double* x,
                           const std::vector<PointField>& fields) {
  if (!std::isfinite(time))
    throw std::invalid_argument("PvdSeries '" + name_ + "': step " +
                                std::to_string(steps_.size()) + " has a non-finite time");
  const std::string file = file_name(".vtu");
  write_vtu((fs::path(directory_) / file).string(), dim, n, x, fields);
  steps_.push_back({time, file});
  return file;
}

void PvdSeries::write() const {
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\">\n"
      << "  <Collection>\n";
  for (const Step& s : steps_)
    xml << "    <DataSet timestep=\"" << shortest(s.time) << "\" group=\"\" part=\"0\" file=\""
        << xml_attribute(s.file) << "\"/>\n";
  xml << "  </Collection>\n"
      << "</VTKFile>\n";

  write_xml(fs::path(directory_) / (name_ + ".pvd"), xml.str(), "ParaView series");
}

void PvdSeries::record(double time, std::string file) {
  if (!std::isfinite(time))
    throw std::invalid_argument("PvdSeries '" + name_ + "': step " + std::to_string(steps_.size()) +
                                " has a non-finite time");
  steps_.push_back({time, std::move(file)});
}

std::string PvdSeries::file_name(const char* extension) const {
  char index[32];
  std::snprintf(index, sizeof index, "_%06zu", steps_.size());
  return name_ + index + extension;
}

void write_pvtu(const std::string& path, const std::vector<std::string>& pieces,
                const std::vector<PointField>& fields) {
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      << "  <PUnstructuredGrid GhostLevel=\"0\">\n"
      << "    <PPointData>\n";
  for (const PointField& f : fields)
    xml << "      <PDataArray type=\"Float64\" Name=\"" << xml_attribute(f.name) << "\" NumberOfComponents=\""
        << f.components << "\"/>\n";
  xml << "    </PPointData>\n"
      << "    <PPoints>\n"
      << "      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
      << "    </PPoints>\n";
  for (const std::string& piece : pieces) xml << "    <Piece Source=\"" << xml_attribute(piece) << "\"/>\n";
  xml << "  </PUnstructuredGrid>\n"
      << "</VTKFile>\n";
  write_xml(path, xml.str(), "ParaView piece list");
}

std::size_t PvdSeries::size() const { return steps_.size(); }

}  // namespace perinom::io

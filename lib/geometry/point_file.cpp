#include "perinom/geometry/point_file.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
    cells.push_back(b == std::string::npos ? std::string() : cell.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

[[noreturn]] void fail(long line, const std::string& what) {
  throw InputError("line " + std::to_string(line) + ": " + what);
}

double number(const std::string& cell, const std::string& column, long line) {
  char* end = nullptr;
  const double v = std::strtod(cell.c_str(), &end);
  if (cell.empty() || *end != '\0' || !std::isfinite(v)) fail(line, column + " must be a finite number, not '" + cell + "'");
  return v;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

/// Opens the file and checks its header against `columns` (plus the optional `extra`).
std::ifstream open_csv(const std::string& path, const std::vector<std::string>& columns, const std::string& extra,
                       bool& has_extra) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open the file");
  std::string header;
  if (!std::getline(in, header)) fail(1, "the file is empty; it starts with the header " + joined(columns));
  // A spreadsheet's UTF-8 byte order mark: invisible in the message that refused the header.
  if (header.compare(0, 3, "\xEF\xBB\xBF") == 0) header.erase(0, 3);
  auto with = columns;
  with.push_back(extra);
  const auto names = split(header);
  has_extra = !extra.empty() && names == with;
  if (names != columns && !has_extra)
    fail(1, "the header must be " + joined(columns) + (extra.empty() ? "" : " (optionally ," + extra + ")") +
                ", not '" + header + "'");
  return in;
}

/// The last facet must lie within kFacetReach sizes (V_i / t)^(1/d) of its particle i (t = 1
/// in 3-D). A facet lies on its particle's cell, half a size away on a square cell and
/// sqrt(r) / 2 sizes on a rectangle of aspect ratio r: the bound admits cells up to r = 64.
/// A facet given to the wrong particle (0 for 9, three horizons off) moved a shear answer by
/// 2.5% while the divergence theorem, which sees only the facets, held.
constexpr double kFacetReach = 4.0;

void check_near_owner(const BoundaryFacets& f, const PointCloud& cloud, double thickness, long line) {
  const int d = cloud.dim;
  const std::size_t k = f.size() - 1, i = f.particle[k];
  double d2 = 0.0;
  for (int a = 0; a < d; ++a) d2 += std::pow(f.centroid[k * d + a] - cloud.x[i * d + a], 2);
  const double size = std::pow(cloud.volume[i] / (d == 2 ? thickness : 1.0), 1.0 / d);
  if (std::sqrt(d2) <= kFacetReach * size) return;
  char at[100], text[400];
  std::snprintf(at, sizeof at, d == 2 ? "(%.6g, %.6g)" : "(%.6g, %.6g, %.6g)", cloud.x[i * d], cloud.x[i * d + 1],
                d == 3 ? cloud.x[i * d + 2] : 0.0);
  std::snprintf(text, sizeof text,
                "the facet is %.6g m from its particle %zu at %s, more than %g times the particle's size "
                "(volume%s)^(1/%d) = %.6g m; a facet lies on its particle's cell: is the particle column the "
                "0-based line of the point file, the header not counted?",
                std::sqrt(d2), i, at, kFacetReach, d == 2 ? " / thickness" : "", d, size);
  fail(line, text);
}

}  // namespace

PointCloud read_point_file(const std::string& path, int dim) {
  std::vector<std::string> columns{"x", "y"};
  if (dim == 3) columns.push_back("z");
  columns.push_back("volume");
  bool unused = false;
  std::ifstream in = open_csv(path, columns, "", unused);
  PointCloud cloud;
  cloud.dim = dim;
  std::string line;
  for (long n = 2; std::getline(in, line); ++n) {
    if (blank(line)) continue;
    const auto cells = split(line);
    if (cells.size() != columns.size())
      fail(n, "expected " + std::to_string(columns.size()) + " values, found " + std::to_string(cells.size()));
    for (int a = 0; a < dim; ++a) cloud.x.push_back(number(cells[a], columns[a], n));
    const double v = number(cells[dim], "volume", n);
    if (!(v > 0.0)) fail(n, "volume must be positive");
    cloud.volume.push_back(v);
  }
  if (cloud.size() == 0) throw InputError("the file holds no particle");
  return cloud;
}

void read_facet_file(const std::string& path, Body& body, double thickness) {
  const int d = body.cloud.dim;
  std::vector<std::string> columns{"particle", "area", "nx", "ny"};
  if (d == 3) columns.push_back("nz");
  for (const char* c : {"x", "y", "z"})
    if (columns.size() < static_cast<std::size_t>(2 + 2 * d)) columns.push_back(c);
  bool grouped = false;
  std::ifstream in = open_csv(path, columns, "group", grouped);
  BoundaryFacets& f = body.facets;
  f.dim = d;
  std::string line;
  for (long n = 2; std::getline(in, line); ++n) {
    if (blank(line)) continue;
    const auto cells = split(line);
    const std::size_t want = columns.size() + (grouped ? 1 : 0);
    if (cells.size() != want) fail(n, "expected " + std::to_string(want) + " values, found " + std::to_string(cells.size()));
    const double p = number(cells[0], "particle", n);
    if (!(p >= 0.0 && p < static_cast<double>(body.cloud.size()) && p == std::floor(p)))
      fail(n, "particle must be a line of the point file, 0 to " + std::to_string(body.cloud.size() - 1));
    const double area = number(cells[1], "area", n);
    if (!(area > 0.0)) fail(n, "area must be positive");
    double normal[3] = {0, 0, 0}, length = 0.0;
    for (int a = 0; a < d; ++a) normal[a] = number(cells[2 + a], columns[2 + a], n), length += normal[a] * normal[a];
    if (!(length > 0.0)) fail(n, "the normal is zero");
    f.particle.push_back(static_cast<ParticleId>(p));
    f.area.push_back(area);
    for (int a = 0; a < d; ++a) f.normal.push_back(normal[a] / std::sqrt(length));
    for (int a = 0; a < d; ++a) f.centroid.push_back(number(cells[2 + d + a], columns[2 + d + a], n));
    check_near_owner(f, body.cloud, thickness, n);
    int side = -1;
    if (grouped && !cells.back().empty()) {
      const FacetGroup* g = find_group(body.groups, cells.back());
      if (!g) body.groups.push_back({cells.back(), {}}), g = &body.groups.back();
      side = 100 + static_cast<int>(g - body.groups.data());
      body.groups[side - 100].facets.push_back(f.size() - 1);
    }
    f.side.push_back(side);
  }
  if (f.empty()) throw InputError("the file holds no facet");
}

}  // namespace perinom

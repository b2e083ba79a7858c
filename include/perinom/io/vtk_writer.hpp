#pragma once
/// @file Point clouds as VTK XML files: one .vtu per output step, a .pvd time series over them.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace perinom::io {

/// One named point-data array, viewed (not owned) for the duration of a write.
/// Layout: n points x `components` doubles, row-major (point-major): data[i*components + c].
/// A field with 9 components is written as the active tensor (XX, XY, XZ, YX, ..., ZZ),
/// one with 3 components as the active vector, so ParaView offers tensor and vector filters.
struct PointField {
  std::string name;    ///< array name shown in ParaView; must be non-empty
  int components = 1;  ///< values per point (1 scalar, dim vector, 9 tensor, ...)
  const double* data = nullptr;  ///< n*components values; may be null only when n == 0
};

/// Writes a VTK XML UnstructuredGrid (.vtu) with one VTK_VERTEX cell per point,
/// binary, appended and zlib-compressed.
/// @param path    target file; written as path + ".tmp", then renamed to path, so a crash
///                never leaves a file that looks complete. The directory must exist.
/// @param dim     2 or 3.
/// @param n       number of points.
/// @param x       n*dim coordinates (m), point-major: x[i*dim + d]; in 2-D, z is written as 0.
/// @param fields  point-data arrays, each holding n*components values.
/// @throws perinom::InputError naming the path if it cannot be written.
/// @throws std::invalid_argument if dim or a field is malformed.
void write_vtu(const std::string& path, int dim, std::size_t n, const double* x,
               const std::vector<PointField>& fields);

/// The .pvtu that makes `pieces` one dataset in ParaView: .vtu files written by write_vtu
/// with these fields (names and components; the data is not read), named relative to the
/// .pvtu's folder. Written via path + ".tmp" and a rename.
/// @throws perinom::InputError naming the path if it cannot be written.
void write_pvtu(const std::string& path, const std::vector<std::string>& pieces,
                const std::vector<PointField>& fields);

/// A ParaView time series: directory/name.pvd lists directory/name_000000.vtu,
/// directory/name_000001.vtu, ... with their times. The directory must exist.
class PvdSeries {
 public:
  PvdSeries(std::string directory, std::string name);

  /// Writes directory/name_<6-digit index>.vtu (see write_vtu) and records it at `time` (s).
  /// The .pvd is not touched; call write() to publish the series.
  /// @returns the file name written, relative to the directory (as listed in the .pvd).
  std::string add(double time, int dim, std::size_t n, const double* x,
                  const std::vector<PointField>& fields);

  /// Records a step written elsewhere (a distributed run's .pvtu over its pieces) at `time`.
  void record(double time, std::string file);
  /// The name the next step's file gets: name_<6-digit index> + extension (".vtu").
  std::string file_name(const char* extension) const;

  /// (Re)writes directory/name.pvd (an XML Collection with relative file names),
  /// via name.pvd.tmp + rename. Safe to call after every add().
  /// @throws perinom::InputError naming the path if it cannot be written.
  void write() const;

  /// Number of steps recorded so far.
  std::size_t size() const;

  /// A recorded step: its time and its file name, relative to the directory.
  struct Step {
    double time;
    std::string file;
  };
  const std::vector<Step>& steps() const { return steps_; }
  /// Continues a series recorded earlier (a checkpoint's): `steps` become this series'
  /// steps, and the next add() writes index steps.size(). No file is touched.
  void resume(std::vector<Step> steps) { steps_ = std::move(steps); }

 private:
  std::string directory_;
  std::string name_;
  std::vector<Step> steps_;
};

}  // namespace perinom::io

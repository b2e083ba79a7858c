#pragma once
/// @file Histories as CSV: one header line, then one row of numbers per recorded step.
#include <cstdio>
#include <string>
#include <vector>

namespace perinom::io {

/// Writes a CSV file to path + ".tmp" and renames it to path on close(), so a file
/// under its final name is always complete. Values are written with full precision
/// (%.17g, so they read back bit for bit); NaN and Inf appear as nan, inf, -inf.
/// Not copyable: it owns the open file.
class CsvWriter {
 public:
  /// Opens path + ".tmp" for writing. The directory must exist.
  /// @throws perinom::InputError naming the path if the file cannot be opened.
  explicit CsvWriter(std::string path);
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  /// If close() was not called (an exception cut the writing short), closes and removes
  /// path + ".tmp": an unfinished file is never published.
  ~CsvWriter();

  /// Writes the column names, once, before any row. Names holding commas, quotes or
  /// line breaks are quoted as in RFC 4180.
  /// @throws std::logic_error if called twice, after a row, or after close().
  void header(const std::vector<std::string>& names);

  /// Writes one row of values.
  /// @throws std::invalid_argument if a header was written and the sizes differ.
  /// @throws std::logic_error after close().
  void row(const std::vector<double>& values);

  /// Flushes, closes and renames path + ".tmp" to path. Idempotent.
  /// @throws perinom::InputError naming the path if writing or renaming failed (the .tmp
  /// file is removed first).
  void close();

  /// The final path (without ".tmp").
  const std::string& path() const { return path_; }

 private:
  void require_open(const char* operation) const;

  std::string path_;
  std::FILE* file_ = nullptr;
  std::size_t columns_ = 0;  ///< header width; 0 while no header was written
  std::size_t rows_ = 0;
};

}  // namespace perinom::io

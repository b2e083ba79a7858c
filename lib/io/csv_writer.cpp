#include "perinom/io/csv_writer.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "perinom/core/error.hpp"

namespace perinom::io {
namespace {

std::string quoted_if_needed(const std::string& name) {
  if (name.find_first_of(",\"\r\n") == std::string::npos) return name;
  std::string out = "\"";
  for (char c : name) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace

CsvWriter::CsvWriter(std::string path) : path_(std::move(path)) {
  const std::string tmp = path_ + ".tmp";
  file_ = std::fopen(tmp.c_str(), "wb");
  if (file_ == nullptr)
    throw InputError("cannot write CSV file '" + path_ + "': opening '" + tmp +
                     "' failed: " + std::strerror(errno));
}

CsvWriter::~CsvWriter() {
  // Not closed: an exception left the file unfinished. It is discarded, not published.
  if (file_ == nullptr) return;
  std::fclose(file_);
  std::error_code ignored;
  std::filesystem::remove(path_ + ".tmp", ignored);
}

void CsvWriter::require_open(const char* operation) const {
  if (file_ == nullptr)
    throw std::logic_error("CsvWriter '" + path_ + "': " + operation + " after close()");
}

void CsvWriter::header(const std::vector<std::string>& names) {
  require_open("header()");
  if (columns_ > 0 || rows_ > 0)
    throw std::logic_error("CsvWriter '" + path_ + "': header() must come once, before any row");
  if (names.empty())
    throw std::invalid_argument("CsvWriter '" + path_ + "': header() needs at least one name");
  std::string line;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) line += ',';
    line += quoted_if_needed(names[i]);
  }
  line += '\n';
  std::fputs(line.c_str(), file_);
  columns_ = names.size();
}

void CsvWriter::row(const std::vector<double>& values) {
  require_open("row()");
  if (columns_ > 0 && values.size() != columns_)
    throw std::invalid_argument("CsvWriter '" + path_ + "': row " + std::to_string(rows_) +
                                " has " + std::to_string(values.size()) +
                                " values, the header has " + std::to_string(columns_));
  for (std::size_t i = 0; i < values.size(); ++i)
    std::fprintf(file_, i > 0 ? ",%.17g" : "%.17g", values[i]);
  std::fputc('\n', file_);
  ++rows_;
}

void CsvWriter::close() {
  if (file_ == nullptr) return;
  const std::string tmp = path_ + ".tmp";
  const bool write_failed = std::ferror(file_) != 0;
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  std::error_code ec, ignored;
  if (write_failed || close_failed) {
    std::filesystem::remove(tmp, ignored);
    throw InputError("cannot write CSV file '" + path_ + "': writing '" + tmp + "' failed");
  }
  std::filesystem::rename(tmp, path_, ec);
  if (ec) {
    std::filesystem::remove(tmp, ignored);
    throw InputError("cannot write CSV file '" + path_ + "': renaming '" + tmp +
                     "' failed: " + ec.message());
  }
}

}  // namespace perinom::io

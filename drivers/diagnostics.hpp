#pragma once
// The warnings and notes of one perinom command. Each is printed on stdout, in order with the
// rest of the run's account ("perinom: warning: ..."), and kept: summary.json lists them, so a
// script that reads the summary sees what the terminal said.
#include <string>

#include "perinom/io/json_writer.hpp"

namespace perinom::cli {

/// Prints "perinom: warning: TEXT" (printf format) and keeps TEXT.
void warn(const char* format, ...) __attribute__((format(printf, 1, 2)));
/// Prints "perinom: note: TEXT" (printf format) and keeps TEXT.
void note(const char* format, ...) __attribute__((format(printf, 1, 2)));

/// summary["warnings"] and summary["notes"]: the texts said so far, in order (empty arrays if none).
void add_diagnostics(io::Json& summary);

}  // namespace perinom::cli

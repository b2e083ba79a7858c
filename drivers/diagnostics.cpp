#include "diagnostics.hpp"

#include <cstdarg>
#include <cstdio>
#include <vector>

namespace perinom::cli {
namespace {

std::vector<std::string> warnings, notes;  // one command per process

void say(const char* kind, std::vector<std::string>& kept, const char* format, va_list args) {
  va_list again;
  va_copy(again, args);
  const int size = std::vsnprintf(nullptr, 0, format, args);
  std::string text(size > 0 ? std::size_t(size) : 0, '\0');
  if (size > 0) std::vsnprintf(text.data(), text.size() + 1, format, again);
  va_end(again);
  std::printf("perinom: %s: %s\n", kind, text.c_str());
  std::fflush(stdout);
  kept.push_back(std::move(text));
}

io::Json list(const std::vector<std::string>& texts) {
  io::Json out = io::Json::array();
  for (const auto& t : texts) out.push_back(t);
  return out;
}

}  // namespace

void warn(const char* format, ...) {
  va_list args;
  va_start(args, format);
  say("warning", warnings, format, args);
  va_end(args);
}

void note(const char* format, ...) {
  va_list args;
  va_start(args, format);
  say("note", notes, format, args);
  va_end(args);
}

void add_diagnostics(io::Json& summary) {
  summary["warnings"] = list(warnings);
  summary["notes"] = list(notes);
}

}  // namespace perinom::cli

#include "perinom/io/json_writer.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "perinom/core/error.hpp"

namespace perinom::io {
namespace {

void append_escaped(std::string& out, const std::string& s) {
  out += '"';
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(c));
          out += buffer;
        } else {
          out += c;  // UTF-8 bytes pass through unchanged
        }
    }
  }
  out += '"';
}

void newline(std::string& out, int indent, int depth) {
  if (indent < 0) return;
  out += '\n';
  out.append(static_cast<std::size_t>(indent) * static_cast<std::size_t>(depth), ' ');
}

}  // namespace

Json::Json() = default;
Json::Json(bool value) : kind_(Kind::Bool), boolean_(value) {}
Json::Json(double value) {
  if (!std::isfinite(value)) return;  // JSON has no NaN or Inf: stay null
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  kind_ = Kind::Number;
  text_.assign(buffer, result.ptr);
}
Json::Json(int value) : kind_(Kind::Number), text_(std::to_string(value)) {}
Json::Json(long value) : kind_(Kind::Number), text_(std::to_string(value)) {}
Json::Json(long long value) : kind_(Kind::Number), text_(std::to_string(value)) {}
Json::Json(unsigned value) : kind_(Kind::Number), text_(std::to_string(value)) {}
Json::Json(unsigned long value) : kind_(Kind::Number), text_(std::to_string(value)) {}
Json::Json(unsigned long long value) : kind_(Kind::Number), text_(std::to_string(value)) {}
Json::Json(const char* value) : kind_(Kind::String), text_(value == nullptr ? "" : value) {}
Json::Json(std::string value) : kind_(Kind::String), text_(std::move(value)) {}

Json Json::object() {
  Json j;
  j.kind_ = Kind::Object;
  return j;
}

Json Json::array() {
  Json j;
  j.kind_ = Kind::Array;
  return j;
}

const char* Json::kind_name() const {
  switch (kind_) {
    case Kind::Null: return "null";
    case Kind::Bool: return "a bool";
    case Kind::Number: return "a number";
    case Kind::String: return "a string";
    case Kind::Array: return "an array";
    case Kind::Object: return "an object";
  }
  return "?";
}

Json& Json::operator[](const std::string& key) {
  if (kind_ == Kind::Null) kind_ = Kind::Object;
  if (kind_ != Kind::Object)
    throw std::logic_error("Json[\"" + key + "\"]: the value is " + kind_name() +
                           ", not an object");
  for (std::size_t i = 0; i < keys_.size(); ++i)
    if (keys_[i] == key) return items_[i];
  keys_.push_back(key);
  items_.emplace_back();
  return items_.back();
}

void Json::push_back(Json value) {
  if (kind_ == Kind::Null) kind_ = Kind::Array;
  if (kind_ != Kind::Array)
    throw std::logic_error(std::string("Json::push_back: the value is ") + kind_name() +
                           ", not an array");
  items_.push_back(std::move(value));
}

std::string Json::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  return out;
}

void Json::dump_to(std::string& out, int indent, int depth) const {
  switch (kind_) {
    case Kind::Null: out += "null"; return;
    case Kind::Bool: out += boolean_ ? "true" : "false"; return;
    case Kind::Number: out += text_; return;
    case Kind::String: append_escaped(out, text_); return;
    case Kind::Array:
    case Kind::Object: break;
  }
  const bool is_object = kind_ == Kind::Object;
  out += is_object ? '{' : '[';
  for (std::size_t i = 0; i < items_.size(); ++i) {
    if (i > 0) out += ',';
    newline(out, indent, depth + 1);
    if (is_object) {
      append_escaped(out, keys_[i]);
      out += indent < 0 ? ":" : ": ";
    }
    items_[i].dump_to(out, indent, depth + 1);
  }
  if (!items_.empty()) newline(out, indent, depth);
  out += is_object ? '}' : ']';
}

void write_json_file(const std::string& path, const Json& json) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw InputError("cannot write JSON file '" + path + "': opening '" + tmp +
                       "' failed: " + std::strerror(errno));
    out << json.dump() << '\n';
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw InputError("cannot write JSON file '" + path + "': writing '" + tmp + "' failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw InputError("cannot write JSON file '" + path + "': renaming '" + tmp +
                     "' failed: " + ec.message());
  }
}

}  // namespace perinom::io

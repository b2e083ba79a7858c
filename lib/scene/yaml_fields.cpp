#include "yaml_fields.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "perinom/core/error.hpp"

namespace perinom::detail {

namespace {

/// The nodes the --set options of the scene being read gave, with their options.
thread_local std::vector<std::pair<YAML::Node, std::string>>* override_nodes = nullptr;

void collect(const YAML::Node& node, const std::string& assignment, std::vector<std::pair<YAML::Node, std::string>>& out) {
  out.emplace_back(node, assignment);
  if (node.IsSequence() || node.IsMap())
    for (const auto& item : node) collect(node.IsMap() ? item.second : item, assignment, out);
}

}  // namespace

OverrideSources::OverrideSources(const std::vector<YAML::Node>& values, const std::vector<std::string>& assignments) {
  override_nodes = new std::vector<std::pair<YAML::Node, std::string>>();
  for (std::size_t k = 0; k < values.size(); ++k) collect(values[k], assignments[k], *override_nodes);
}

OverrideSources::~OverrideSources() {
  delete override_nodes;
  override_nodes = nullptr;
}

std::string where(const std::string& source, const YAML::Node& node) {
  if (override_nodes && node.IsDefined())
    for (const auto& given : *override_nodes)
      if (node.is(given.first)) return "--set " + given.second + ": ";
  const auto m = node.Mark();
  if (m.line < 0) return source + ": ";
  return source + ":" + std::to_string(m.line + 1) + ": ";
}

Fields::Fields(const YAML::Node& node, std::string path, std::string source)
    : node_(node), path_(std::move(path)), source_(std::move(source)) {
  if (!node_.IsMap())
    throw InputError(where(source_, node_) + (path_.empty() ? "scene" : path_) +
                     ": must be a mapping of keys to values");
  // yaml-cpp keeps the first of two equal keys and drops the second silently.
  std::set<std::string> seen;
  for (const auto& kv : node_) {
    // YAML allows a list or a mapping as a key ("[a, b]: c", "? [a, b]"); a scene does not.
    if (!kv.first.IsScalar()) {
      YAML::Emitter flow;
      flow << YAML::Flow << kv.first;
      throw InputError(where(source_, kv.first) + key(flow.c_str()) +
                       ": a key must be a plain name, not a list or a mapping");
    }
    const std::string k = kv.first.as<std::string>();
    if (!seen.insert(k).second)
      throw InputError(where(source_, kv.first) + key(k) + ": key given twice");
  }
}

namespace {

/// Why a scalar is not read as a double: its text out of a double's range (1e400 was called
/// "not a number", or "not a list of 2 numbers" inside a list), or `what`.
std::string why_not_a_double(const YAML::Node& n, const std::string& what) {
  if (!n.IsScalar()) return what;
  const std::string text = n.Scalar();
  errno = 0;
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  if (!text.empty() && end == text.c_str() + text.size() && errno == ERANGE)
    return "'" + text + "' is out of the range of a double (magnitudes 2.2e-308 to 1.8e308, or 0)";
  return what;
}

}  // namespace

bool Fields::has(const std::string& k) const { return node_[k].IsDefined() && !node_[k].IsNull(); }

void Fields::fail(const std::string& k, const std::string& what) const {
  const YAML::Node n = node_[k];
  throw InputError(where(source_, n.IsDefined() ? n : node_) + key(k) + ": " + what);
}

YAML::Node Fields::get(const std::string& k, bool required) {
  used_.insert(k);
  const YAML::Node n = node_[k];
  if (required && (!n.IsDefined() || n.IsNull())) fail(k, "required key is missing");
  return n;
}

double Fields::number(const std::string& k) {
  const YAML::Node n = get(k, true);
  try {
    if (!n.IsScalar()) throw YAML::Exception(n.Mark(), "");
    const double v = n.as<double>();
    if (!std::isfinite(v)) fail(k, "must be a finite number");
    return v;
  } catch (const YAML::Exception&) {
    fail(k, why_not_a_double(n, "must be a number"));
  }
}

double Fields::number(const std::string& k, double fallback) {
  return has(k) ? number(k) : (used_.insert(k), fallback);
}

std::int64_t Fields::integer(const std::string& k) {
  const YAML::Node n = get(k, true);
  try {
    if (!n.IsScalar()) throw YAML::Exception(n.Mark(), "");
    return n.as<std::int64_t>();
  } catch (const YAML::Exception&) {
    fail(k, "must be a whole number");
  }
}

std::int64_t Fields::integer(const std::string& k, std::int64_t fallback) {
  return has(k) ? integer(k) : (used_.insert(k), fallback);
}

int Fields::small_integer(const std::string& k, int fallback) {
  const std::int64_t v = integer(k, fallback);
  if (v > 1000000000 || v < -1000000000) fail(k, "is out of range");
  return static_cast<int>(v);
}

bool Fields::boolean(const std::string& k, bool fallback) {
  const YAML::Node n = get(k, false);
  if (!n.IsDefined()) return fallback;
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    fail(k, "must be true or false");
  }
}

std::string Fields::text(const std::string& k) {
  const YAML::Node n = get(k, true);
  if (!n.IsScalar()) fail(k, "must be a string");
  return n.as<std::string>();
}

std::string Fields::text(const std::string& k, const std::string& fallback) {
  return has(k) ? text(k) : (used_.insert(k), fallback);
}

std::array<double, 3> Fields::vector(const std::string& k, int n) {
  const YAML::Node v = get(k, true);
  if (!v.IsSequence() || static_cast<int>(v.size()) != n)
    fail(k, "must be a list of " + std::to_string(n) + " numbers");
  std::array<double, 3> out{0, 0, 0};
  for (int a = 0; a < n; ++a) {
    try {
      out[a] = v[a].as<double>();
    } catch (const YAML::Exception&) {
      fail(k, why_not_a_double(v[a], "must be a list of " + std::to_string(n) + " numbers"));
    }
    if (!std::isfinite(out[a])) fail(k, "must hold finite numbers");
  }
  return out;
}

Fields Fields::map(const std::string& k) {
  const YAML::Node n = get(k, true);
  if (!n.IsMap()) fail(k, "must be a mapping of keys to values");
  return Fields(n, key(k), source_);
}

std::vector<YAML::Node> Fields::list(const std::string& k) {
  const YAML::Node n = get(k, false);
  std::vector<YAML::Node> out;
  if (!n.IsDefined() || n.IsNull()) return out;
  if (!n.IsSequence()) fail(k, "must be a list");
  for (const auto& item : n) out.push_back(item);
  return out;
}

void Fields::finish() const {
  for (const auto& kv : node_) {
    const std::string k = kv.first.as<std::string>();
    // null counts as absent, for a key this section reads only elsewhere too (damage.f_t:
    // null with the stretch criterion read "unknown key").
    if (!used_.count(k) && !kv.second.IsNull())
      throw InputError(where(source_, kv.first) + key(k) + ": unknown key");
  }
}

void require_closed_quotes(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  char open = 0;  // the quote of the string being read, or 0
  int open_line = 0, number = 0, flow = 0, block_indent = -1;
  for (std::string l; std::getline(in, l);) {
    ++number;
    const std::size_t first = l.find_first_not_of(" \t\r");
    const int indent = first == std::string::npos ? -1 : static_cast<int>(first);
    // The lines of a block scalar (key: | or key: >) are text: quotes in them mean nothing.
    if (open == 0 && block_indent >= 0) {
      if (indent < 0 || indent > block_indent) continue;
      block_indent = -1;
    }
    bool start = true;  // where a scalar, and so a quoted string, may begin
    for (std::size_t i = 0; i < l.size(); ++i) {
      const char c = l[i];
      const bool space_after = i + 1 == l.size() || l[i + 1] == ' ' || l[i + 1] == '\t' || l[i + 1] == '\r';
      if (open == '"') {
        if (c == '\\') ++i;
        else if (c == '"') open = 0, start = false;
        continue;
      }
      if (open == '\'') {
        if (c == '\'' && i + 1 < l.size() && l[i + 1] == '\'') ++i;
        else if (c == '\'') open = 0, start = false;
        continue;
      }
      if (c == ' ' || c == '\t' || c == '\r') continue;
      if (c == '#' && (i == 0 || l[i - 1] == ' ' || l[i - 1] == '\t')) break;
      if (start && (c == '"' || c == '\'')) {
        open = c, open_line = number;
        continue;
      }
      if (start && (c == '|' || c == '>')) {
        block_indent = indent;
        break;
      }
      if (c == '[' || c == '{') ++flow, start = true;
      else if (c == ']' || c == '}') flow = std::max(0, flow - 1), start = false;
      else if (c == ',') start = flow > 0;
      else if (c == ':' || c == '-' || c == '?') start = space_after;
      else start = false;
    }
  }
  if (open != 0)
    throw InputError(source + ":" + std::to_string(open_line) + ": not valid YAML: the " +
                     (open == '"' ? "double" : "single") + "-quoted string that starts on this line is never closed");
}

YAML::Node apply_override(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set " + assignment + ": expected dotted.key=value");
  const std::string path = assignment.substr(0, eq);
  // An empty value read as YAML is null, which counts as absent: `solver.type=` ran ADR and
  // `stages=` a scene without loads, with exit 0, and `boundary.0.pressure=` blamed the file.
  if (assignment.find_first_not_of(" \t", eq + 1) == std::string::npos)
    throw InputError("--set " + path + ": no value after '=' (to remove an optional key, write " + path + "=null)");
  // A space in the key (' material.nu', from a quoted word) made it a key of the file's.
  if (path.find_first_of(" \t") != std::string::npos)
    throw InputError("--set '" + path + "': a key has no spaces (expected dotted.key=value)");
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw InputError("--set " + path + ": the value is not valid YAML (" + e.msg + ")");
  }
  // Error messages name list items as boundary[1].pressure; --set takes that form too.
  std::string dotted;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i] != '[') {
      dotted += path[i];
      continue;
    }
    const auto close = path.find(']', i);
    const std::string digits = close == std::string::npos ? "" : path.substr(i + 1, close - i - 1);
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos ||
        (close + 1 < path.size() && path[close + 1] != '.'))
      throw InputError("--set " + path + ": a list item is named by its index, as boundary.1.pressure or boundary[1].pressure");
    dotted += "." + digits;
    i = close;
  }
  std::vector<std::string> parts;
  for (std::size_t start = 0;;) {
    const auto dot = dotted.find('.', start);
    parts.push_back(dotted.substr(start, dot - start));
    if (parts.back().empty()) throw InputError("--set " + path + ": an empty key between dots (expected dotted.key=value)");
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  try {
    set_path(root, parts, value, path);
  } catch (const YAML::Exception& e) {
    throw InputError("--set " + path + ": cannot set this key (" + e.msg + ")");
  }
  return value;
}

void set_path(YAML::Node& root, const std::vector<std::string>& parts, const YAML::Node& value,
              const std::string& path) {
  YAML::Node cur = root;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const std::string& part = parts[p];
    const bool index = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
    if (!index && cur.IsDefined() && !cur.IsNull() && !cur.IsMap())
      throw InputError("--set " + path + ": '" + part + "' is a key inside something that is not a mapping");
    if (index && !cur.IsSequence())
      throw InputError("--set " + path + ": '" + part + "' indexes something that is not a list");
    // Compared as text first: an index of twenty digits does not fit any integer type.
    std::size_t at = 0;
    if (index) {
      const std::string size = std::to_string(cur.size());
      const std::size_t lead = std::min(part.find_first_not_of('0'), part.size() - 1);
      const std::string digits = part.substr(lead);
      if (digits.size() > size.size() || (digits.size() == size.size() && digits >= size))
        throw InputError("--set " + path + ": list index " + part + " is out of range (the list has " + size +
                         " items)");
      at = std::stoul(digits);
    }
    if (p + 1 == parts.size()) {
      if (index) cur[at] = value;
      else cur[part] = value;
    } else {
      YAML::Node next = index ? cur[at] : cur[part];
      cur.reset(next);
    }
  }
}

}  // namespace perinom::detail

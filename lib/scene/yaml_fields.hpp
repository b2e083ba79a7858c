#pragma once
// Strict access to one YAML mapping: typed reads that name the dotted key and line in
// every error, and a final check that no unknown key was left unread.
#include <yaml-cpp/yaml.h>

#include <array>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace perinom::detail {

class Fields {
 public:
  /// node must be a mapping; path is its dotted key ("" at the top), source the file name.
  Fields(const YAML::Node& node, std::string path, std::string source);

  bool has(const std::string& key) const;
  double number(const std::string& key);  // required
  double number(const std::string& key, double fallback);
  std::int64_t integer(const std::string& key, std::int64_t fallback);
  std::int64_t integer(const std::string& key);  // required
  /// A required or defaulted whole number that must fit in an int.
  int small_integer(const std::string& key, int fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string text(const std::string& key);      // required
  std::string text(const std::string& key, const std::string& fallback);
  /// A list of exactly n numbers.
  std::array<double, 3> vector(const std::string& key, int n);
  Fields map(const std::string& key);  // required mapping
  std::vector<YAML::Node> list(const std::string& key);  // optional list (empty if absent)
  YAML::Node node(const std::string& key) const { return node_[key]; }
  void mark(const std::string& key) { used_.insert(key); }

  /// Throws for the first key that was never read.
  void finish() const;

  std::string key(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }
  /// "file:line: dotted.key: what"
  [[noreturn]] void fail(const std::string& k, const std::string& what) const;
  const std::string& source() const { return source_; }

 private:
  YAML::Node get(const std::string& key, bool required);
  YAML::Node node_;
  std::string path_, source_;
  std::set<std::string> used_;
};

/// Sets root[parts[0]][parts[1]]... = value (numeric parts index lists).
void set_path(YAML::Node& root, const std::vector<std::string>& parts, const YAML::Node& value,
              const std::string& path);

/// Applies one "dotted.key=value" override to the YAML tree; returns the value's node.
YAML::Node apply_override(YAML::Node& root, const std::string& assignment);

/// While alive, where() names the nodes of these overrides (each value's node and the nodes
/// inside it) by their --set option, not by a line of the scene file (a bad --set value was
/// reported at line 1 of the file).
class OverrideSources {
 public:
  OverrideSources(const std::vector<YAML::Node>& values, const std::vector<std::string>& assignments);
  ~OverrideSources();
  OverrideSources(const OverrideSources&) = delete;
  OverrideSources& operator=(const OverrideSources&) = delete;
};

/// yaml-cpp reads a quoted string that is never closed to the end of the file, taking every
/// key below it as text. Throws an InputError naming the line where such a quote opens.
void require_closed_quotes(const std::string& text, const std::string& source);

/// "file:line: " for a node (line counted from 1), "--set key=value: " for a node a --set
/// gave (OverrideSources), or "file: " when unknown.
std::string where(const std::string& source, const YAML::Node& node);

}  // namespace perinom::detail

#include "perinom/scene/scene_difference.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>

namespace perinom {
namespace {

std::string flow(const YAML::Node& n) {
  if (!n.IsDefined()) return "absent";
  if (n.IsScalar()) return n.Scalar();
  if (n.IsNull()) return "null";
  YAML::Emitter out;
  out << YAML::Flow << n;
  return out.c_str();
}

std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

std::optional<SceneDifference> differ(const std::string& path, const YAML::Node& a, const YAML::Node& b) {
  const auto here = [&] { return SceneDifference{path, flow(a), flow(b)}; };
  // A key one scene lacks is an undefined node, whose Type() would throw.
  if (!a.IsDefined() || !b.IsDefined() || a.Type() != b.Type()) return here();
  if (a.IsScalar()) {
    if (a.Scalar() != b.Scalar()) return here();
    return std::nullopt;
  }
  if (a.IsSequence()) {
    for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
      if (auto d = differ(join(path, std::to_string(k)), a[k], b[k])) return d;
    if (a.size() != b.size())
      return SceneDifference{path, std::to_string(a.size()) + " items", std::to_string(b.size()) + " items"};
    return std::nullopt;
  }
  if (a.IsMap()) {
    for (const auto& item : a) {
      const std::string key = item.first.as<std::string>();
      if (auto d = differ(join(path, key), item.second, b[key])) return d;
    }
    for (const auto& item : b) {
      const std::string key = item.first.as<std::string>();
      if (!a[key].IsDefined()) return SceneDifference{join(path, key), "absent", flow(item.second)};
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<SceneDifference> scene_difference(const std::string& first, const std::string& second) {
  if (first == second) return std::nullopt;
  const auto load = [](const std::string& text, std::string& failure) {
    try {
      return YAML::Load(text);
    } catch (const YAML::Exception& e) {
      failure = "not YAML (" + e.msg + ")";
      return YAML::Node();
    }
  };
  std::string bad_first, bad_second;
  const YAML::Node a = load(first, bad_first), b = load(second, bad_second);
  if (!bad_first.empty() || !bad_second.empty())
    return SceneDifference{"", bad_first.empty() ? "a scene" : bad_first, bad_second.empty() ? "a scene" : bad_second};
  return differ("", a, b);
}

}  // namespace perinom

#pragma once
/// @file Where two scenes differ, by key: why a checkpoint does not belong to a scene.
#include <optional>
#include <string>

namespace perinom {

/// The first key at which two scenes differ, with its value in each ("absent" where a
/// scene lacks it; lists and mappings in YAML flow style).
struct SceneDifference {
  std::string key;  ///< dotted, list items by index ("boundary.1.pressure"); "" for the whole scene
  std::string first, second;
};

/// Compares two canonical scene texts (Scene::canonical) key by key, in the first one's
/// order, then the keys only the second has: empty when they hold the same keys and values,
/// in whatever order. Scalars are compared as written ("1e9" and "1.0e9" differ).
std::optional<SceneDifference> scene_difference(const std::string& first, const std::string& second);

}  // namespace perinom

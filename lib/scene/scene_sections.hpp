#pragma once
// The scene reader's list sections, read strictly like the rest (yaml_fields.hpp).
#include <string>
#include <vector>

#include "perinom/scene/scene.hpp"
#include "yaml_fields.hpp"

namespace perinom::detail {

/// The axis index of "x", "y", "z" in a dim-dimensional scene, or -1.
int axis_of(const std::string& component, int dim);
/// The items of a boundary list; key names the list in messages ("boundary",
/// "stages[1].boundary").
std::vector<BoundarySpec> read_boundary(const std::vector<YAML::Node>& items, const std::string& source,
                                        const Scene& s, const std::string& key = "boundary");
/// f's `region` key: a side, all, {box}, {point} or {group} (groups need a body from files).
Region read_region(Fields& f, const Scene& s);
/// `stages`: each with its name, steps and boundary list.
void read_stages(const std::vector<YAML::Node>& items, const std::string& source, Scene& s);
/// model.type correspondence: its keys (registry.hpp), and what it needs of a body from files.
void read_correspondence_model(Fields& f, Scene& s);
void check_body_formulation(const YAML::Node& root, const Scene& s);
/// A correspondence model's boundary item after region, fix and displacement: traction,
/// pressure and `at` (layer | face).
void read_body_boundary(Fields& f, const Scene& s, BoundarySpec& b);
/// `damage` and `precracks` (after the model, solver and output), and the checks on prescribed
/// velocities (scene_fracture.cpp).
void read_fracture(Fields& top, Scene& s);
/// `probes`.
void read_probes(const std::vector<YAML::Node>& items, const std::string& source, Scene& s);

}  // namespace perinom::detail

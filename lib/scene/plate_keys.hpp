#pragma once
// The scene keys of model.type thin_plate (docs/scene-format.md), read strictly like the rest.
#include "perinom/scene/scene.hpp"
#include "yaml_fields.hpp"

namespace perinom::detail {

/// model: type thin_plate takes only `stabilization` (C_hg of the operator energy).
void read_plate_model(Fields& f, Scene& s);
/// A plate's boundary item: region, `support` (simply_supported | clamped, on a side) and
/// `pressure` (transverse, on the nodes of any region); the elasticity keys are refused.
void read_plate_boundary(Fields& f, const Scene& s, BoundarySpec& b);
/// What a plate needs of the sections read before the model: dimension 2, a box without
/// holes, no jitter, an explicit geometry.thickness (the plate's), a linear elastic material
/// without a plane condition.
void check_plate_scene(const YAML::Node& root, const Scene& s);

}  // namespace perinom::detail

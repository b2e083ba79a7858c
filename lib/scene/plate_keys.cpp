#include "plate_keys.hpp"

namespace perinom::detail {

void read_plate_model(Fields& f, Scene& s) {
  for (const char* k : {"formulation", "stabilization_storage", "weight_precision", "operator_order"})
    if (f.has(k)) f.fail(k, "is a correspondence option; a thin_plate has only stabilization");
  s.model.stabilization = f.number("stabilization", s.model.stabilization);
  if (s.model.stabilization < 0.0) f.fail("stabilization", "must be zero or positive");
  f.finish();
}

void read_plate_boundary(Fields& f, const Scene&, BoundarySpec& b) {
  for (const char* k : {"fix", "displacement", "traction", "at"})
    if (f.has(k)) f.fail(k, "a thin_plate boundary item takes region, support and pressure");
  if (f.has("support")) {
    const std::string s = f.text("support");
    if (s == "simply_supported") b.support = EdgeSupport::simply_supported;
    else if (s == "clamped") b.support = EdgeSupport::clamped;
    else f.fail("support", "must be simply_supported or clamped (an edge without support is free)");
    if (!b.region.is_side) f.fail("support", "holds a side of the plate (left, right, bottom, top)");
  }
  if (f.has("pressure")) b.pressure = f.number("pressure");
  f.finish();
}

void check_plate_scene(const YAML::Node& root, const Scene& s) {
  Fields top(root, "", s.source), geometry(root["geometry"], "geometry", s.source),
      disc(root["discretization"], "discretization", s.source), material(root["material"], "material", s.source);
  if (s.dim != 2) top.fail("dimension", "a thin_plate is two-dimensional (its mid-plane)");
  if (s.body_files.given()) geometry.fail(geometry.has("mesh") ? "mesh" : "points", "a thin_plate is a rectangle (geometry.box)");
  if (!geometry.has("thickness")) geometry.fail("thickness", "is required for a thin_plate: the plate thickness t (m)");
  if (!s.geometry.holes.empty()) geometry.fail("holes", "a thin_plate is a rectangle without holes");
  if (s.discretization.jitter > 0.0) disc.fail("jitter", "must be 0 for a thin_plate (its edge nodes lie on the edges)");
  if (s.plasticity) material.fail("type", "a thin_plate is linear_elastic");
  if (material.has("plane")) material.fail("plane", "a thin_plate has no plane condition");
}

}  // namespace perinom::detail

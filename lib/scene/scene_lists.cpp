// The scene's lists: boundary conditions (with their regions), load stages and probes.
#include <cmath>
#include <set>

#include "perinom/core/error.hpp"
#include "perinom/scene/registry.hpp"
#include "scene_sections.hpp"

namespace perinom::detail {

int axis_of(const std::string& c, int dim) {
  const int a = (c == "x") ? 0 : (c == "y") ? 1 : (c == "z") ? 2 : -1;
  return a < dim ? a : -1;
}

Region read_region(Fields& f, const Scene& s) {
  Region r;
  const YAML::Node n = f.node("region");
  f.mark("region");
  if (!n.IsDefined() || n.IsNull()) f.fail("region", "required key is missing");
  if (n.IsScalar() && n.as<std::string>() == "all") {
    r.is_side = false;
    r.min.fill(-INFINITY);
    r.max.fill(INFINITY);
    return r;
  }
  const bool body = s.body_files.given();
  if (n.IsScalar() && body)
    f.fail("region", "'" + n.as<std::string>() + "': a body from geometry." + (s.body_files.mesh.empty() ? "points" : "mesh") +
                         " has no box sides; name a boundary group ({group: NAME}), all, or a box");
  if (n.IsScalar()) {
    r.is_side = true;
    if (!parse_side(n.as<std::string>(), s.dim, r.side))
      f.fail("region", "unknown side '" + n.as<std::string>() +
                           "' (left, right, bottom, top" + (s.dim == 3 ? ", front, back" : "") +
                           ", or xmin ... zmax)");
    return r;
  }
  if (!n.IsMap()) f.fail("region", "must be a side name, all, {box: {min, max}}, {point: [...]} or {group: NAME}");
  Fields rf(n, f.key("region"), f.source());
  if (rf.has("group")) {
    r.is_side = false;
    if (rf.has("box") || rf.has("point")) rf.fail("group", "give exactly one of group, box or point");
    r.group = rf.text("group");
    if (r.group.empty()) rf.fail("group", "must name a group");
    if (!body) rf.fail("group", "names a boundary group of geometry.mesh or geometry.facets; a box has sides (top, left, ...)");
    rf.finish();
    return r;
  }
  if (rf.has("box") == rf.has("point")) f.fail("region", "give exactly one of box, point or group");
  r.is_side = false;
  if (rf.has("point")) {
    r.is_point = true;
    r.point = rf.vector("point", s.dim);
    rf.finish();
    return r;
  }
  Fields box = rf.map("box");
  r.min = box.vector("min", s.dim);
  r.max = box.vector("max", s.dim);
  box.finish();
  rf.finish();
  return r;
}

std::vector<BoundarySpec> read_boundary(const std::vector<YAML::Node>& items, const std::string& source,
                                        const Scene& s, const std::string& key) {
  std::vector<BoundarySpec> out;
  for (std::size_t k = 0; k < items.size(); ++k) {
    Fields f(items[k], key + "[" + std::to_string(k) + "]", source);
    BoundarySpec b;
    b.where = detail::where(source, items[k]) + key + "[" + std::to_string(k) + "]";
    b.key = key + "." + std::to_string(k);
    for (std::size_t at = b.key.find('['); at != std::string::npos; at = b.key.find('['))
      b.key.replace(at, 1, ".");
    for (std::size_t at = b.key.find(']'); at != std::string::npos; at = b.key.find(']')) b.key.erase(at, 1);
    b.region = read_region(f, s);
    // (An empty list held nothing and was still reported as a support; a component twice
    // is a typo for another.)
    const std::string components = "x, y" + std::string(s.dim == 3 ? ", z" : "");
    if (f.has("fix") && f.list("fix").empty()) f.fail("fix", "names no component: give some of " + components + ", or leave fix out");
    for (const auto& c : f.list("fix")) {
      const int a = c.IsScalar() ? axis_of(c.as<std::string>(), s.dim) : -1;
      if (a < 0) f.fail("fix", "components must be among " + components);
      if (b.fix[a]) f.fail("fix", "names " + c.as<std::string>() + " twice");
      b.fix[a] = true;
    }
    for (const char* key : {"displacement", "velocity"}) {
      if (!f.has(key)) continue;
      Fields d = f.map(key);
      auto& target = std::string(key) == "velocity" ? b.velocity : b.displacement;
      for (const char* c : {"x", "y", "z"}) {
        const int a = axis_of(c, s.dim);
        if (a >= 0 && d.has(c)) target[a] = d.number(c);
      }
      d.finish();
    }
    for (int a = 0; a < s.dim; ++a)
      if (b.velocity[a] && b.displacement[a])
        f.fail("velocity", "prescribes the same component as displacement (give one of the two)");
    find_model(s.model.type)->read_boundary(f, s, b);
    out.push_back(b);
  }
  return out;
}

void read_body_boundary(Fields& f, const Scene& s, BoundarySpec& b) {
  if (f.has("support")) f.fail("support", "edge supports belong to model.type thin_plate (here: fix or displacement)");
  if (f.has("traction")) b.traction = f.vector("traction", s.dim);
  if (f.has("pressure")) b.pressure = f.number("pressure");
  const std::string at = f.text("at", "layer");
  if (at != "layer" && at != "face") f.fail("at", "must be layer or face");
  b.at_face = at == "face";
  const bool surface = b.region.is_side || b.region.is_group();
  if (b.at_face && !surface) f.fail("at", "face needs a side region (top, left, ...) or a group ({group: NAME})");
  if ((b.traction || b.pressure) && !surface)
    f.fail("region", "a traction or pressure acts on a side of the box (top, left, ...) or a group of facets ({group: NAME})");
  f.finish();
}

void read_stages(const std::vector<YAML::Node>& items, const std::string& source, Scene& s) {
  if (!items.empty() && !find_model(s.model.type)->stages)
    throw InputError(detail::where(source, items[0]) + "stages: a " + s.model.type +
                     " is loaded in one stage (solver.load_steps)");
  for (std::size_t k = 0; k < items.size(); ++k) {
    const std::string key = "stages[" + std::to_string(k) + "]";
    Fields f(items[k], key, source);
    StageSpec st;
    st.where = detail::where(source, items[k]) + key;
    st.name = f.text("name", "stage " + std::to_string(k + 1));
    st.steps = f.small_integer("steps", 1);
    if (st.steps < 1) f.fail("steps", "must be at least 1");
    st.boundary = read_boundary(f.list("boundary"), source, s, key + ".boundary");
    f.finish();
    s.stages.push_back(st);
  }
}

namespace {

/// The file a probe writes: probe_NAME.csv for a line, probe_NAME_history.csv for a point (on
/// a load path).
std::string probe_file(const ProbeSpec& p) { return "probe_" + p.name + (p.is_line ? ".csv" : "_history.csv"); }

/// Whether `stem` is a snapshot's of the scene `scene`: scene_ and six or more digits.
bool snapshot_stem(const std::string& scene, const std::string& stem) {
  const std::size_t n = scene.size() + 1;
  return stem.size() >= n + 6 && stem.compare(0, n, scene + "_") == 0 &&
         stem.find_first_not_of("0123456789", n) == std::string::npos;
}

}  // namespace

void read_probes(const std::vector<YAML::Node>& items, const std::string& source, Scene& s) {
  for (std::size_t k = 0; k < items.size(); ++k) {
    Fields f(items[k], "probes[" + std::to_string(k) + "]", source);
    ProbeSpec p;
    p.where = detail::where(source, items[k]) + "probes[" + std::to_string(k) + "]";
    p.name = f.text("name");
    if (p.name.empty() || p.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") != std::string::npos)
      f.fail("name", "must be made of letters, digits, '_', '-' and '.' (it names a file)");
    for (const auto& q : s.probes)
      if (q.name == p.name) f.fail("name", "another probe is already named '" + p.name + "'");
    p.is_line = f.has("line");
    if (p.is_line == f.has("point"))
      f.fail(p.is_line ? "line" : "point", std::string("a probe has exactly one of point or line; this one has ") +
                                               (p.is_line ? "both" : "neither"));
    // The files probes write, apart from one another and from the snapshots' NAME_NNNNNN.csv.
    for (const auto& q : s.probes)
      if (probe_file(q) == probe_file(p))
        f.fail("name", probe_file(p) + " is probe '" + q.name + "''s file already (a line probe writes probe_NAME.csv, "
                       "a point probe on a load path probe_NAME_history.csv)");
    if (p.is_line && snapshot_stem(s.name, "probe_" + p.name))
      f.fail("name", probe_file(p) + " is the name of a snapshot's .csv of the scene '" + s.name + "' (output.csv)");
    if (p.is_line) {
      Fields l = f.map("line");
      p.from = l.vector("from", s.dim);
      p.to = l.vector("to", s.dim);
      l.finish();
    } else {
      p.point = f.vector("point", s.dim);
    }
    const ModelEntry& model = *find_model(s.model.type);
    p.field = f.text("field", model.probe_field);
    if (model.probe_field_only && p.field != model.probe_field)
      f.fail("field", "a " + model.name + " probe measures the " + model.probe_field + " (field: " + model.probe_field + ")");
    for (const ModelEntry& other : model_registry())
      if (other.probe_field_only && &other != &model && p.field == other.probe_field)
        f.fail("field", p.field + " is the field of a " + other.name + " (model.type: " + other.name + ")");
    p.reconstruct = f.boolean("reconstruct", p.reconstruct);
    if (p.reconstruct && (p.is_line || (p.field != "displacement" && p.field != "stress" &&
                                         p.field != "von_mises" && p.field != "mean_stress")))
      f.fail("reconstruct", "only point probes of the displacement, stress, von_mises or mean_stress are reconstructed");
    if (p.field == "deflection") {
      if (f.has("component")) f.fail("component", "a deflection probe has no component");
    } else if (p.field == "displacement") {
      p.component = f.text("component", p.is_line ? "x" : "");
      if (axis_of(p.component, s.dim) < 0) f.fail("component", "must be x, y" + std::string(s.dim == 3 ? " or z" : ""));
    } else if (p.field == "stress") {
      p.component = f.text("component");
      const std::set<std::string> ok = {"xx", "yy", "zz", "xy", "yz", "xz", "yx", "zy", "zx"};
      if (!ok.count(p.component) || (s.dim == 2 && p.component.find('z') != std::string::npos &&
                                     p.component != "zz"))
        f.fail("component", s.dim == 2 ? "must be xx, yy, zz or xy" : "must be xx, yy, zz, xy, yz or xz");
    } else if (p.field == "von_mises" || p.field == "mean_stress" || p.field == "equivalent_strain" ||
               p.field == "eq_plastic_strain") {
      if (f.has("component"))
        f.fail("component", (p.field[0] == 'e' ? "an " : "a ") + p.field + " probe has no component");
      if (p.field == "eq_plastic_strain" && !s.plasticity)
        f.fail("field", "eq_plastic_strain needs a plastic material (material.type: drucker_prager)");
    } else {
      f.fail("field", "must be displacement, stress, von_mises, mean_stress, equivalent_strain or eq_plastic_strain");
    }
    f.finish();
    s.probes.push_back(p);
  }
}


}  // namespace perinom::detail

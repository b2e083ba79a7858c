// The scene's fracture keys (issue 17): `damage` (which bonds break during a Verlet run),
// `precracks` (bonds cut at build time), and the checks that prescribed velocities need.
#include <cmath>

#include "perinom/core/error.hpp"
#include "scene_sections.hpp"

namespace perinom::detail {
namespace {

double norm(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/// Bonds break in the model's graph and its rows are refreshed: the classical formulation of
/// a correspondence model. The consistent G~ comes from a global correction (no local
/// refresh), and the improved and strong formulations' surface band and the consistent
/// formulation's facets would not follow the crack faces.
void require_breakable_model(Fields& top, const Scene& s, const std::string& key) {
  if (s.model.type != "correspondence")
    top.fail(key, "bonds break in a correspondence model, not in a " + s.model.type);
  if (s.model.formulation != "classical")
    top.fail(key, "needs model.formulation classical (here " + s.model.formulation +
                      "): the consistent formulation's corrected G and the improved and strong formulations' "
                      "surface terms do not follow new crack faces");
  if (s.model.operator_order == 2 && s.model.stabilization > 0.0 && s.model.stabilization_storage != "matrix_free")
    top.fail(key, "with model.operator_order 2 the stabilization must be stored matrix_free to follow broken bonds "
                  "(model.stabilization_storage: matrix_free)");
}

Precrack read_precrack(Fields& f, int dim) {
  Precrack c;
  if (dim == 2) {
    const auto from = f.vector("from", 2), to = f.vector("to", 2);
    c.origin = from;
    for (int a = 0; a < 2; ++a) c.edge1[a] = to[a] - from[a];
    if (!(norm(c.edge1) > 0.0)) f.fail("to", "must differ from `from` (a crack of zero length)");
  } else {
    c.origin = f.vector("origin", 3);
    c.edge1 = f.vector("edge1", 3);
    c.edge2 = f.vector("edge2", 3);
    const std::array<double, 3>& a = c.edge1;
    const std::array<double, 3>& b = c.edge2;
    const std::array<double, 3> n{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    if (!(norm(a) > 0.0)) f.fail("edge1", "must be nonzero (the two edges span the crack's rectangle)");
    if (!(norm(b) > 0.0)) f.fail("edge2", "must be nonzero (the two edges span the crack's rectangle)");
    if (!(norm(n) > 1e-12 * norm(a) * norm(b)))
      f.fail("edge2", "is parallel to edge1: the two edges must span a rectangle");
  }
  f.finish();
  return c;
}

}  // namespace

void read_fracture(Fields& top, Scene& s) {
  if (top.has("damage")) {
    Fields f = top.map("damage");
    DamageSpec d;
    d.criterion = f.text("criterion");
    if (d.criterion == "instability") {
      d.s_max = f.number("s_max");
      if (!(d.s_max > 0.0)) f.fail("s_max", "must be positive");
    } else if (d.criterion == "stretch") {
      if (f.has("s_c") == f.has("G_c")) f.fail("criterion", "stretch needs exactly one of s_c and G_c");
      if (f.has("s_c")) {
        d.s_c = f.number("s_c");
        if (!(d.s_c > 0.0)) f.fail("s_c", "must be positive");
      } else {
        d.G_c = f.number("G_c");  // s_c follows from the families (problem.cpp)
        if (!(d.G_c > 0.0)) f.fail("G_c", "must be positive");
      }
    } else if (d.criterion == "stress") {
      d.f_t = f.number("f_t");
      if (!(d.f_t > 0.0)) f.fail("f_t", "must be positive");
      if (f.has("fracture_energy")) {
        d.fracture_energy = f.number("fracture_energy");
        if (!(d.fracture_energy > 0.0)) f.fail("fracture_energy", "must be positive");
      }
    } else {
      f.fail("criterion", "must be instability, stretch or stress");
    }
    if (d.criterion != "stress" && f.has("fracture_energy"))
      f.fail("fracture_energy", "softens the bonds the stress criterion breaks (criterion: stress)");
    // Another criterion's key: said as such (it read "unknown key").
    for (const auto& [key, owner] : {std::pair{"s_max", "instability"}, {"s_c", "stretch"}, {"G_c", "stretch"},
                                     {"f_t", "stress"}})
      if (d.criterion != owner && f.has(key))
        f.fail(key, std::string("belongs to criterion: ") + owner + ", not " + d.criterion);
    d.every = f.integer("every", 1);
    if (d.every < 1) f.fail("every", "must be at least 1");
    const std::vector<YAML::Node> keep = f.list("no_fail");
    for (std::size_t k = 0; k < keep.size(); ++k) {
      Fields item(keep[k], f.key("no_fail") + "[" + std::to_string(k) + "]", s.source);
      d.no_fail.push_back(read_region(item, s));
      d.no_fail_where.push_back(detail::where(s.source, keep[k]) + f.key("no_fail") + "[" + std::to_string(k) + "]");
      if (d.no_fail.back().is_group()) item.fail("region", "a no-fail zone is a side, a box or a point, not a group");
      item.finish();
    }
    f.finish();
    // Quasi-static breaking: a load path (stages) balanced by ADR or LBC, each step a fixed
    // point of balance and breaking (solve_load_path).
    const bool load_path = !s.stages.empty() && (s.solver.type == "adr" || s.solver.type == "lbc");
    if (s.solver.type != "verlet" && !load_path)
      top.fail("damage", "bonds break during a Verlet run (solver.type verlet) or on a load path (stages, solved by "
                         "adr or lbc), not with solver.type " + s.solver.type + (s.stages.empty() ? " without stages" : ""));
    if (load_path && s.plasticity && s.solver.check == "newton")
      top.fail("damage", "solver.check: newton with drucker_prager and breaking bonds is not built (the plastic "
                         "path depends on when each bond broke, and the check solves the broken body at its final "
                         "loads); remove solver.check");
    if (d.fracture_energy > 0.0) {
      // What the softening bonds are not built for yet (models/cohesive_bonds.hpp).
      const auto refuse = [&](const std::string& what) {
        f.fail("fracture_energy", "softening bonds " + what + " are not built; remove fracture_energy for the plain "
                                  "stress criterion");
      };
      if (!load_path) refuse("in a Verlet run (their dissipation is not in its energy balance)");
      if (s.plasticity) refuse("in a drucker_prager body");
    }
    if (load_path && d.every != 1)
      f.fail("every", "applies to Verlet steps; a load path looks for bonds to break after every balance");
    require_breakable_model(top, s, "damage");
    s.damage = d;
  }
  const std::vector<YAML::Node> cracks = top.list("precracks");
  for (std::size_t k = 0; k < cracks.size(); ++k) {
    Fields f(cracks[k], "precracks[" + std::to_string(k) + "]", s.source);
    s.precracks.push_back(read_precrack(f, s.dim));
  }
  if (!cracks.empty()) require_breakable_model(top, s, "precracks");
  for (const BoundarySpec& b : s.boundary)
    for (int a = 0; a < s.dim; ++a) {
      if (!b.velocity[a]) continue;
      if (s.solver.type != "verlet")
        throw InputError(b.where + ".velocity: a prescribed velocity needs solver.type verlet");
      if (b.at_face) throw InputError(b.where + ".velocity: is prescribed at the particles (at: layer), not at a face");
      if (s.model.type != "correspondence")
        throw InputError(b.where + ".velocity: is for a correspondence model");
    }
  for (const StageSpec& st : s.stages)
    for (const BoundarySpec& b : st.boundary)
      for (int a = 0; a < s.dim; ++a)
        if (b.velocity[a]) throw InputError(b.where + ".velocity: load stages are quasi-static; velocities need Verlet");
}

}  // namespace perinom::detail

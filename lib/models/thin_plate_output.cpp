// What the drivers and solvers ask of a thin plate through Model: its output fields, its
// moments as the stress measure, its lines of the plan (rigidity, nodes and ghosts, edges),
// and the supports that stop its rigid motions.
#include <cstdio>

#include "perinom/models/thin_plate.hpp"

namespace perinom {
namespace {

/// (xx, xy, yy) per node into row-major 3 x 3 tensors.
std::vector<double> tensor9(const std::vector<double>& t3) {
  const std::size_t n = t3.size() / 3;
  std::vector<double> t(n * 9, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    t[i * 9 + 0] = t3[i * 3];
    t[i * 9 + 1] = t[i * 9 + 3] = t3[i * 3 + 1];
    t[i * 9 + 4] = t3[i * 3 + 2];
  }
  return t;
}

const char* support_name(EdgeSupport e) {
  return e == EdgeSupport::clamped ? "clamped" : e == EdgeSupport::simply_supported ? "simply supported" : "free";
}

}  // namespace

std::vector<OutputField> ThinPlateModel::output_fields(const double* w, bool, bool) const {
  const std::size_t n = particles();
  std::vector<double> w3(n * 3, 0.0), t3(n * 3), volume(n);
  for (std::size_t i = 0; i < n; ++i) w3[i * 3 + 2] = w[i];
  for (std::size_t i = 0; i < n; ++i) volume[i] = plate_.area[i] * opt_.thickness;
  curvature(w, t3.data());
  std::vector<double> kappa9 = tensor9(t3);
  moments(w, t3.data());
  return {{"deflection", 1, std::vector<double>(w, w + n)},
          {"displacement", 3, std::move(w3)},
          {"curvature", 9, std::move(kappa9)},
          {"moment", 9, tensor9(t3)},
          {"volume", 1, std::move(volume)}};
}

std::vector<double> ThinPlateModel::stress_measure(const double* w) const {
  std::vector<double> M(particles() * 3);
  moments(w, M.data());
  return M;
}

std::vector<PlanLine> ThinPlateModel::plan() const {
  char model[200], nodes[200], edges[200];
  std::snprintf(model, sizeof model, "thin_plate, D0 = %.6g N m, thickness %g m, stabilization C_hg = %g", D0_,
                opt_.thickness, opt_.stabilization);
  std::snprintf(nodes, sizeof nodes, "%ld x %ld (on the edges), %zu ghost nodes outside the supported edges",
                plate_.nodes[0], plate_.nodes[1], plate_.image.size());
  const PlateEdges& e = opt_.edges;
  std::snprintf(edges, sizeof edges, "left %s, right %s, bottom %s, top %s", support_name(e[0]), support_name(e[1]),
                support_name(e[2]), support_name(e[3]));
  return {{"dimension", ", thin plate"}, {"model", model}, {"plate nodes", nodes}, {"edges", edges}};
}

std::vector<std::string> ThinPlateModel::not_assembled() const {
  std::vector<std::string> items = {"gradient operator G and stabilization S of elasticity (no correspondence model)"};
  if (opt_.stabilization <= 0.0) items.push_back("plate stabilization (C_hg = 0)");
  return items;
}

std::string ThinPlateModel::support_advice() const {
  const PlateEdges& e = opt_.edges;
  char advice[400];
  std::snprintf(advice, sizeof advice,
                "support more edges, boundary items {region: left, right, bottom or top, support: simply_supported or "
                "clamped}, to stop the plate translating along z and turning about axes in its plane (a plate takes "
                "no fix); its edges now: left %s, right %s, bottom %s, top %s",
                support_name(e[0]), support_name(e[1]), support_name(e[2]), support_name(e[3]));
  return advice;
}

}  // namespace perinom

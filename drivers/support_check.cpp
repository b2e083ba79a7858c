#include "support_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "perinom/fracture/pieces.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/models/rigid_body.hpp"
#include "perinom/models/thin_plate.hpp"

namespace perinom::cli {
namespace {

/// A vector of d components, scaled so its largest is 1 (a direction), as "(a, b, c)".
std::string direction(const std::array<double, 3>& v, int d) {
  double top = 0.0;
  for (int a = 0; a < d; ++a)
    if (std::abs(v[a]) > std::abs(top)) top = v[a];
  std::string out = "(";
  char buf[32];
  for (int a = 0; a < d; ++a) {
    const double c = top != 0.0 ? v[a] / top : 0.0;
    std::snprintf(buf, sizeof buf, "%s%.3g", a ? ", " : "", std::abs(c) < 5e-4 ? 0.0 : c);
    out += buf;
  }
  return out + ")";
}

/// A point as "(x, y, z) m", rounding's residue below 1e-9 of its largest coordinate shown as 0.
std::string point(const std::array<double, 3>& p, int d) {
  double top = 0.0;
  for (int a = 0; a < d; ++a) top = std::max(top, std::abs(p[a]));
  std::string out = "(";
  char buf[32];
  for (int a = 0; a < d; ++a) {
    std::snprintf(buf, sizeof buf, "%s%.6g", a ? ", " : "", std::abs(p[a]) <= 1e-9 * top ? 0.0 : p[a]);
    out += buf;
  }
  return out + ") m";
}

std::string describe(const FreeRigidMotion& f, int d) {
  if (!f.turns) return "move along " + direction(f.translation, d);
  if (d == 2) return "turn about " + point(f.point, d);
  return "turn about the axis along " + direction(f.rotation, d) + " through " + point(f.point, d);
}

std::string describe(const std::vector<FreeRigidMotion>& free, int d) {
  std::string text;
  for (std::size_t k = 0; k < free.size(); ++k) text += (k ? "; " : "") + describe(free[k], d);
  return text;
}

/// Warns of the free motions of the body (a plate's when `plate` is set), saying where.
bool check(const PointCloud& cloud, const ThinPlateModel* plate, const Loading& loading, const std::string& where) {
  const std::vector<FreeRigidMotion> free =
      plate ? free_plate_motions(plate->plate(), loading) : free_rigid_motions(cloud, loading);
  if (free.empty()) return false;
  const std::string text = describe(free, plate ? 3 : cloud.dim);
  std::fprintf(stderr,
               "perinom: warning: %s: the supports leave the %s %zu rigid motion(s) free: it can %s. A static "
               "balance needs every rigid motion held: a load along one%s will not balance (%s)\n",
               where.c_str(), plate ? "plate" : "body", free.size(), text.c_str(),
               plate ? "" : ", or a crack that frees a piece,",
               plate ? "support more edges, or clamp one"
                     : "hold more components, or use constraints: rigid_body for a body without supports");
  return true;
}

}  // namespace

bool warn_if_free(const Problem& p) {
  const auto* plate = dynamic_cast<const ThinPlateModel*>(p.model.get());
  if (!plate && p.physics().dofs_per_particle() != p.cloud.dim) return false;
  if (p.stages.empty()) return check(p.cloud, plate, p.loading, "boundary");
  bool any = false;
  for (const LoadStage& st : p.stages) any = check(p.cloud, plate, st.loading, "stage '" + st.name + "'") || any;
  return any;
}

bool explain_free_pieces(const Problem& p, const History& steps) {
  const auto* model = dynamic_cast<const CorrespondenceModel*>(p.model.get());
  if (!model || p.stages.empty() || p.physics().dofs_per_particle() != p.cloud.dim) return false;
  // The stage that failed: the last balanced step's (column "stage" counts from 1), or the
  // next one when that step ended it.
  std::size_t k = 0;
  if (steps.rows() > 0) {
    const std::size_t last = steps.rows() - 1;
    k = std::min(static_cast<std::size_t>(std::max(steps.at(last, steps.column("stage")), 1.0)) - 1, p.stages.size() - 1);
    if (static_cast<int>(steps.at(last, steps.column("step"))) >= p.stages[k].steps && k + 1 < p.stages.size()) ++k;
  }
  const NonlocalOperator& G = model->G();
  const Pieces pieces = body_pieces(G.graph(), G.detached());
  const int d = p.cloud.dim;
  int named = 0, more = 0;
  for (std::int32_t c = 0; c < pieces.count; ++c) {
    std::vector<std::uint8_t> within(p.cloud.size(), 0);
    std::size_t n = 0;
    std::array<double, 3> at{0, 0, 0};
    for (std::size_t i = 0; i < p.cloud.size(); ++i)
      if (pieces.piece[i] == c) {
        within[i] = 1, ++n;
        for (int a = 0; a < d; ++a) at[a] += p.cloud.x[i * d + a];
      }
    const std::vector<FreeRigidMotion> free = free_rigid_motions(p.cloud, p.stages[k].loading, within);
    if (free.empty()) continue;
    if (named == 3) {
      ++more;
      continue;
    }
    for (int a = 0; a < d; ++a) at[a] /= static_cast<double>(n);
    std::printf("perinom: note: in stage '%s' the cracks have left a piece of %zu particle(s) around %s (of %d "
                "piece(s), %zu detached particle(s) apart) that its supports do not hold: it can %s\n",
                p.stages[k].name.c_str(), n, point(at, d).c_str(), static_cast<int>(pieces.count),
                G.detached().size(), describe(free, d).c_str());
    ++named;
  }
  if (more > 0) std::printf("perinom: note: and %d more such piece(s)\n", more);
  return named > 0;
}

}  // namespace perinom::cli

#include "support_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "perinom/models/rigid_body.hpp"

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

bool check(const PointCloud& cloud, const Loading& loading, const std::string& where) {
  const std::vector<FreeRigidMotion> free = free_rigid_motions(cloud, loading);
  if (free.empty()) return false;
  std::string text;
  for (std::size_t k = 0; k < free.size(); ++k) text += (k ? "; " : "") + describe(free[k], cloud.dim);
  std::fprintf(stderr,
               "perinom: warning: %s: the supports leave the body %zu rigid motion(s) free: it can %s. A static "
               "balance needs every rigid motion held: a load along one, or a crack that frees a piece, will not "
               "balance (hold more components, or use constraints: rigid_body for a body without supports)\n",
               where.c_str(), free.size(), text.c_str());
  return true;
}

}  // namespace

bool warn_if_free(const Problem& p) {
  if (p.physics().dofs_per_particle() != p.cloud.dim) return false;
  if (p.stages.empty()) return check(p.cloud, p.loading, "boundary");
  bool any = false;
  for (const LoadStage& st : p.stages) any = check(p.cloud, st.loading, "stage '" + st.name + "'") || any;
  return any;
}

}  // namespace perinom::cli

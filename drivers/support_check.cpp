#include "support_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "perinom/fracture/pieces.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/models/rigid_body.hpp"
#include "perinom/models/thin_plate.hpp"
#include "diagnostics.hpp"

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

/// One piece of the body: its particles (flags), how many, and their centroid.
struct Piece {
  std::vector<std::uint8_t> within;
  std::size_t count = 0;
  std::array<double, 3> centroid{0, 0, 0};
};

Piece piece_of(const PointCloud& cloud, const Pieces& pieces, std::int32_t c) {
  const int d = cloud.dim;
  Piece out;
  out.within.assign(cloud.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (pieces.piece[i] == c) {
      out.within[i] = 1, ++out.count;
      for (int a = 0; a < d; ++a) out.centroid[a] += cloud.x[i * d + a];
    }
  for (int a = 0; a < d; ++a) out.centroid[a] /= static_cast<double>(std::max<std::size_t>(out.count, 1));
  return out;
}

/// The pieces of an intact correspondence body (joined by its bonds; a precrack may cut it),
/// or none for other models.
Pieces intact_pieces(const Problem& p) {
  const auto* model = dynamic_cast<const CorrespondenceModel*>(p.model.get());
  return model ? body_pieces(model->G().graph(), {}) : Pieces{};
}

/// Warns of the free motions of each piece of a body in pieces (no bond joins them: a mesh of
/// two parts, a precrack across): a piece held in y only stood still in the whole body's
/// check, which counted the other piece's supports, and ADR ran its 200,000 iterations.
bool check_pieces(const Problem& p, const Pieces& pieces, const Loading& loading, const std::string& where) {
  const int d = p.cloud.dim;
  bool any = false;
  for (std::int32_t c = 0; c < pieces.count; ++c) {
    const Piece piece = piece_of(p.cloud, pieces, c);
    const std::vector<FreeRigidMotion> free = free_rigid_motions(p.cloud, loading, piece.within);
    if (free.empty()) continue;
    warn("%s: the body is in %d pieces that no bond joins, and the supports leave the piece "
                 "of %zu particle(s) around %s %zu rigid motion(s) free: it can %s. A static balance needs every "
                 "piece held (hold more components of that piece)",
                 where.c_str(), static_cast<int>(pieces.count), piece.count, point(piece.centroid, d).c_str(),
                 free.size(), describe(free, d).c_str());
    any = true;
  }
  return any;
}

/// Warns of the free motions of the body (a plate's when `plate` is set), saying where.
bool check(const PointCloud& cloud, const PlateCloud* plate, const Loading& loading, const std::string& where) {
  const std::vector<FreeRigidMotion> free =
      plate ? free_plate_motions(*plate, loading) : free_rigid_motions(cloud, loading);
  if (free.empty()) return false;
  const std::string text = describe(free, plate ? 3 : cloud.dim);
  warn("%s: the supports leave the %s %zu rigid motion(s) free: it can %s. A static "
               "balance needs every rigid motion held: a load along one%s will not balance (%s)",
               where.c_str(), plate ? "plate" : "body", free.size(), text.c_str(),
               plate ? "" : ", or a crack that frees a piece,",
               plate ? "support more edges, or clamp one"
                     : "hold more components, or use constraints: rigid_body for a body without supports");
  return true;
}

/// `one(loading, where)` for each loading of the run (each stage's, or the scene's).
template <class One>
bool each_loading(const Problem& p, One one) {
  if (p.stages.empty()) return one(p.loading, "boundary");
  bool any = false;
  for (const LoadStage& st : p.stages) any = one(st.loading, "stage '" + st.name + "'") || any;
  return any;
}

}  // namespace

bool warn_if_free(const Problem& p) {
  const auto* model = dynamic_cast<const ThinPlateModel*>(p.model.get());
  if (!model && p.physics().dofs_per_particle() != p.cloud.dim) return false;
  const PlateCloud* plate = model ? &model->plate() : nullptr;
  const Pieces pieces = plate ? Pieces{} : intact_pieces(p);
  return each_loading(p, [&](const Loading& loading, const std::string& where) {
    return pieces.count > 1 ? check_pieces(p, pieces, loading, where) : check(p.cloud, plate, loading, where);
  });
}

bool warn_if_free_frame(const Problem& frame, const PlateCloud* plate) {
  return each_loading(frame, [&](const Loading& loading, const std::string& where) {
    return check(frame.cloud, plate, loading, where);
  });
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
    const Piece piece = piece_of(p.cloud, pieces, c);
    const std::vector<FreeRigidMotion> free = free_rigid_motions(p.cloud, p.stages[k].loading, piece.within);
    if (free.empty()) continue;
    if (named == 3) {
      ++more;
      continue;
    }
    note("in stage '%s' the cracks have left a piece of %zu particle(s) around %s (of %d "
                "piece(s), %zu detached particle(s) apart) that its supports do not hold: it can %s",
                p.stages[k].name.c_str(), piece.count, point(piece.centroid, d).c_str(), static_cast<int>(pieces.count),
                G.detached().size(), describe(free, d).c_str());
    ++named;
  }
  if (more > 0) note("and %d more such piece(s)", more);
  return named > 0;
}

}  // namespace perinom::cli

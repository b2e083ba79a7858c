#pragma once
/// @file Regions that select particles: a side of the box, a box selector, or the particle
/// nearest a point.
#include <array>
#include <string>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/lattice.hpp"

namespace perinom {

/// A side of the box: the outermost particle layer at the min or max of one axis.
/// Names: left/right (x), bottom/top (y in 2-D, z in 3-D), front/back (y in 3-D),
/// and the explicit xmin, xmax, ymin, ymax, zmin, zmax.
struct Side {
  int axis = 0;
  bool at_max = false;
};

/// Parses a side name for a box of dimension dim; returns false if the name is unknown.
bool parse_side(const std::string& name, int dim, Side& side);

/// A region: a side of the geometry's box, an axis-aligned selector box, (is_point) the one
/// particle nearest a point, which stays the same material point when dx changes, or (when
/// `group` is not empty) a named group of boundary facets of a mesh or facet file
/// (geometry/body.hpp).
struct Region {
  bool is_side = true;
  bool is_point = false;
  Side side;
  std::array<double, 3> min{0, 0, 0}, max{0, 0, 0};  ///< selector box (m), inclusive
  std::array<double, 3> point{0, 0, 0};              ///< is_point: the point (m)
  std::string group;  ///< a facet group's name; is_side is then false
  bool is_group() const { return !group.empty(); }
};

/// The particles a side, box or point region selects (not a group: see group_particles). A
/// side selects the layer within one spacing of the face; a point the nearest particle
/// (nearest_particle: the lowest index on a tie).
std::vector<ParticleId> select(const Region& region, const BoxGeometry& box,
                               const PointCloud& cloud);

/// The particle nearest a point (reference positions; the lowest index on a tie, to 1e-9 of
/// the spacing), its distance from the point, and that particle's spacing: the distance to its
/// d-th nearest neighbour (a lattice's spacing; in a smaller cloud its farthest; infinite in a
/// cloud of one). Rounding broke ties before: the notched beam's point supports, midway between
/// two columns at every spacing, landed on different sides, its span 122.5 mm at dx = 2.5 mm
/// and 125 at 1.25 (now 125 at every spacing, both supports half a spacing to the left), and a
/// scene in mm chose another particle than the same scene in m.
struct NearestParticle {
  ParticleId id = 0;
  double distance = 0.0;
  double spacing = 0.0;
};
NearestParticle nearest_particle(const PointCloud& cloud, const double* point);

/// Every particle as near the point as the nearest (`nearest`, of nearest_particle), to 1e-9
/// of its spacing, in index order: one, or on a tie all of them (a point midway between two
/// lattice columns, a corner of four cells).
std::vector<ParticleId> nearest_particles(const PointCloud& cloud, const double* point, const NearestParticle& nearest);

/// A point on the body or its surface lies within about a spacing of its nearest particle
/// (0.87 of one at a 3-D lattice's corner). Empty when it lies within two; otherwise what is
/// wrong, for an error naming the key: "is D m from the nearest particle (R of its spacings;
/// particle N at (x, y)): outside the body or in a hole".
std::string outside_body(const NearestParticle& nearest, const PointCloud& cloud);

/// A point outside the box by more than `slack` (and rounding, 1e-9 of its largest side): "lies D
/// m outside geometry.box (past its max x = X m)"; empty otherwise. outside_body lets a point
/// two spacings off pass, and a reconstructed probe there extrapolates past the surface.
std::string outside_box(const BoxGeometry& box, const double* point, double slack = 0.0);

/// A point inside one of the box's holes (deeper than 1e-6 of its radius: a point on the
/// edge is on the body): "lies inside hole K (centre (...), radius R m)"; empty otherwise. A
/// small hole's centre is within two spacings of the edge particles, which outside_body lets
/// pass (a probe at the centre of a hole of radius 1.5 dx read the edge particle, exit 0).
std::string inside_hole(const BoxGeometry& box, const double* point);

/// Outward unit normal of a side (dim entries).
std::array<double, 3> outward_normal(const Side& side);

}  // namespace perinom

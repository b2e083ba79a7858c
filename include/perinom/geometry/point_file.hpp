#pragma once
/// @file Particles and boundary facets read from CSV files (a body from another program).
#include <string>

#include "perinom/geometry/body.hpp"

namespace perinom {

/// Particles from a CSV file: a header line with the columns `x,y,volume` (2-D) or
/// `x,y,z,volume` (3-D), then one particle per line: position (m) and volume (m^3; in 2-D
/// the area times the thickness, as every particle volume). Blank lines are skipped.
/// Throws InputError ("line N: ...", without the path) for a missing file, another header,
/// a value that is not a finite number, a volume that is not positive, or no particle.
PointCloud read_point_file(const std::string& path, int dim);

/// Boundary facets from a CSV file for the particles of `cloud`: a header with the columns
/// `particle,area,nx,ny,x,y` (2-D) or `particle,area,nx,ny,nz,x,y,z` (3-D), optionally
/// followed by `group`; then one facet per line: the owning particle (0-based line of the
/// point file), area (m^2; 2-D: length times thickness), outward normal (normalized on
/// reading), centroid (m), and the name of its group (empty: none). Groups are listed in
/// the order first met. Facet side codes are 100 + the group index, or -1. A facet farther
/// from its particle i than 4 (V_i / thickness)^(1/d) (thickness 1 in 3-D; m) is refused: a
/// facet lies on its particle's cell, and the bound admits cells of aspect ratio up to 64.
void read_facet_file(const std::string& path, Body& body, double thickness);

}  // namespace perinom

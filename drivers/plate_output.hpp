#pragma once
// What a thin_plate run writes: its VTK fields and its probe values.
#include <string>
#include <vector>

#include "perinom/io/json_writer.hpp"
#include "perinom/io/vtk_writer.hpp"
#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// The point data of a plate snapshot at deflection w: deflection (m), displacement (0, 0, w)
/// for ParaView's Warp By Vector, curvature (1/m) and moment (N m / m) as 3 x 3 tensors (zz,
/// xz, yz zero), volume (quadrature area times thickness). The arrays live in this object.
struct PlateFields {
  std::vector<double> w3, kappa9, moment9;
  PlateFields(const Problem& p, const std::vector<double>& w);
  std::vector<io::PointField> list(const Problem& p, const std::vector<double>& w) const;
};

/// The plate's probes: point probes print and return w at their node; line probes also
/// write probe_NAME.csv (s, x, y, z, deflection).
io::Json plate_probe_results(const Problem& p, const std::vector<double>& w, const std::string& dir);

}  // namespace perinom::cli

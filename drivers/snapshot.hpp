#pragma once
// What `perinom run` writes of a state: VTK point data, probe values.
#include <string>
#include <vector>

#include "perinom/io/json_writer.hpp"
#include "perinom/io/vtk_writer.hpp"
#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// Adds one snapshot at `time` to the series and rewrites the .pvd: the model's output fields
/// at u (Model::output_fields: a solid's displacement, stress, von Mises and mean stress,
/// volume, its surface stress, subregions and plastic fields where it has them; a plate's
/// deflection, curvature and moments). With output.csv the same point data also go to
/// dir/NAME_<index>.csv (the .vtu's name with .csv), one row per particle, for scripts.
/// @throws SolveError naming the field and particle, before writing anything, if a field
/// holds NaN or Inf (the solvers treat it as a failed NaN/Inf guard).
void add_snapshot(io::PvdSeries& series, double time, const Problem& p, const std::vector<double>& u,
                  const std::string& dir = "");

/// A snapshot's point data as CSV, one row per particle of `cloud`: x, y, z, then each
/// field's components (NAME, or NAME_0, NAME_1, ... for several).
void write_snapshot_csv(const std::string& path, const PointCloud& cloud, const std::vector<io::PointField>& fields);

}  // namespace perinom::cli

#pragma once
/// @file A thin_plate scene in two steps: the whole plate without its model (the frame), and
/// the model of the whole plate (build_plate_problem) or of a distributed rank's part of it.
#include <cstddef>
#include <memory>

#include "perinom/geometry/plate_cloud.hpp"
#include "perinom/models/thin_plate.hpp"
#include "perinom/neighbors/local_part.hpp"
#include "perinom/scene/problem.hpp"

namespace perinom {

struct PlateFrame {
  /// The physical nodes (cloud, quadrature volumes), the edge conditions and the pressure as
  /// a loading, the probes; no model.
  Problem problem;
  PlateCloud plate;  ///< the nodes and the mirror ghosts
  int layers = 0;    ///< the ghost layers made
  ThinPlateOptions options;
};

/// Throws InputError naming discretization.dx for a plate too small for its ghost layers.
PlateFrame plate_frame(const Scene& scene);

/// The families of `plate` (the frame's plate or a part of it: sub_plate); InputError naming
/// the horizon when one of the first `rows` nodes reaches beyond the ghost layers.
Families plate_families(const Scene& scene, const PlateFrame& frame, const PlateCloud& plate, std::size_t rows);

/// The model of `plate` (InputError naming the horizon for a singular fit).
std::unique_ptr<ThinPlateModel> plate_model(const Scene& scene, PlateCloud plate, const Families& families,
                                            const ThinPlateOptions& options);

/// A distributed rank's local plate model (issue 19) for `part` of the frame's physical nodes
/// (local_part of them, cut at the horizon): `plate` is sub_plate(frame.plate,
/// part.particles) (the part's nodes and their mirrors), `families` plate_families of it
/// over the owned and near nodes; fitted at the owned and near nodes only
/// (ThinPlateOptions::fitted_rows), whose families the part holds whole. Radius families
/// only (std::logic_error for k nearest: they are searched on the whole plate).
std::unique_ptr<ThinPlateModel> plate_part_model(const Scene& scene, const PlateFrame& frame, const LocalPart& part,
                                                 PlateCloud plate, const Families& families);

}  // namespace perinom

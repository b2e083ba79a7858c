#pragma once
// Whether a small-strain answer can be the body's: a result whose displacement gradient is
// not small (E in MPa with lengths in m, a load a thousand times too large) solves the linear
// equations exactly and means nothing; without this check it ended with exit 0 and a tip
// deflection two thousand times the beam's length.
#include <cstddef>
#include <vector>

#include "perinom/io/json_writer.hpp"
#include "perinom/models/model.hpp"
#include "perinom/scene/problem.hpp"
#include "distributed_output.hpp"

namespace perinom::cli {

/// Beyond this |grad u| (Frobenius norm) at a particle, strains and rotations are not small.
inline constexpr double kSmallGradientLimit = 0.1;
/// Beyond this many thicknesses of deflection a plate stretches as it bends (membrane action).
inline constexpr double kSmallDeflectionLimit = 0.5;

/// The largest measure of a state's smallness: |grad u| over the particles that have lost no
/// bond (a crack's opening is not a strain), from the model's `displacement_gradient` output
/// field, or a thin plate's |w| (its `deflection` field); over the first `particles` of the
/// model's fields (a rank's owned ones). `kind` none: not measured (no such field, or
/// `kinematics: finite_rotation`).
struct SmallStrainMeasure {
  enum class Kind { none, gradient, deflection } kind = Kind::none;
  double value = 0.0;
  std::size_t particle = 0;  ///< where it is largest (the caller's numbering)
};
SmallStrainMeasure measure_small_strain(const Scene& scene, const Model& model, const double* u, std::size_t particles);

/// Writes summary["largest_displacement_gradient"] = {value, particle, position} (a plate:
/// "largest_deflection", with over_thickness) and prints a warning naming the particle when
/// the limit is exceeded; `m.particle` indexes p.cloud.
void report_small_strain(const Problem& p, const SmallStrainMeasure& m, io::Json& summary);

/// A serial run: measure_small_strain over every particle, then report_small_strain.
void check_small_strain(const Problem& p, const std::vector<double>& u, io::Json& summary);

/// A distributed run (every rank calls it, u its owned state): each rank measures its owned
/// particles, the largest over the ranks is reported by all (the lowest rank holding it names
/// the particle, in the whole cloud's numbering).
void check_small_strain_over_ranks(const RankRun& run, const std::vector<double>& u, io::Json& summary);

}  // namespace perinom::cli

#pragma once
// The model `perinom bench force` times, serial or distributed: a unit elastic solid with
// the command's stabilization options on radius families of horizon ratio 3.015.
#include <cmath>
#include <cstddef>

#include "commands.hpp"
#include "perinom/core/error.hpp"
#include "perinom/models/correspondence.hpp"

namespace perinom::cli {

constexpr double bench_horizon = 3.015;  ///< horizon over the spacing (the spacing is 1)

inline LinearElastic bench_material(int d) {
  LinearElastic mat;
  mat.E = 1.0;
  mat.nu = 0.25;
  mat.density = 1.0;
  mat.dim = d;
  mat.plane = d == 2 ? PlaneCondition::strain : PlaneCondition::none;
  return mat;
}

inline CorrespondenceOptions bench_options(const Options& opt) {
  CorrespondenceOptions copt;
  copt.stabilization = opt.stabilization;
  if (!parse_stabilization_storage(opt.storage, copt.stabilization_storage))
    throw InputError("--storage must be auto, fused, assembled or matrix_free");
  copt.weight_precision = opt.single_precision ? WeightPrecision::float32 : WeightPrecision::float64;
  return copt;
}

/// The displacement every force benchmark evaluates at: 1e-3 sin(0.37 k) at dof k of the cloud.
inline double bench_displacement(std::size_t dof) { return 1e-3 * std::sin(0.37 * double(dof)); }

}  // namespace perinom::cli

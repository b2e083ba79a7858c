#pragma once
/// @file What a singular Newton stiffness means, said once for KLU, UMFPACK and PETSc.
#include <string>

#include "perinom/models/model.hpp"

namespace perinom::detail {

/// Called when a Newton step's factorization finds the stiffness singular (`factor` says how:
/// "condition number 3.1e+17, estimated from KLU's factors"). An elastic body's stiffness does not change with the
/// load, so a missing support is the cause: throws InputErrorOnEveryRank (exit 2; `factor`
/// is the same on every rank: MUMPS's count of null pivots is global). A plastic body's
/// tangent loses stiffness as it yields: past its limit load a mechanism flows, and the step
/// has no balanced state. Returns that failure's text for the solver's report (exit 3, the
/// last good state written), naming the load step.
std::string singular_stiffness(const Model& model, int step, const std::string& factor);

}  // namespace perinom::detail

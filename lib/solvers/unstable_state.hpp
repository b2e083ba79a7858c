#pragma once
/// @file Why a load path failed from a state it had balanced: the state may be an unstable
/// equilibrium. Internal to lib/solvers.
#include <string>
#include <vector>

#include "perinom/models/loading.hpp"
#include "perinom/models/model.hpp"

namespace perinom::detail {

/// The most free dofs the diagnosis factors: a sparse LDL^T of the stiffness's symmetric part,
/// as the stability check's (docs/verification/stability.md: 12 s at 20,416 free dofs in 2-D;
/// 1.6 s at 1,872 in 3-D, where the fill grows faster: 6 minutes at 15,168). A larger body goes
/// unexamined: a failure's report must not take longer than the run.
inline constexpr std::size_t kUnstableStateDofs2D = 20000;
inline constexpr std::size_t kUnstableStateDofs3D = 4000;

/// At a state u the path balanced (loading at load factor s), the number of independent
/// directions x with x^T K_T x < 0, K_T the reduced tangent there (the negative eigenvalues of
/// its symmetric part, by Sylvester's inertia): a stiffness that gives way, so the state is an
/// unstable equilibrium, which ADR's damped dynamics leaves and where Newton's tangent turns
/// singular as the load goes on. Returns "" when there is none, or when the model has no
/// tangent, has more free dofs than the limits above, or the factorization fails (the
/// diagnosis never becomes an error of its own); else "an unstable equilibrium: <why>", for
/// "the state left is ..." after a failure or "the end state is ..." after a path.
/// Not collective: the caller runs it on a whole model only (not on an MPI rank's part).
std::string unstable_state(Model& model, const Loading& loading, double s, const std::vector<double>& u);

}  // namespace perinom::detail

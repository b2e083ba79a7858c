#include "unstable_state.hpp"

#include <cstdio>
#include <exception>

#include "galerkin.hpp"
#include "inertia.hpp"
#include "perinom/models/tangent_model.hpp"
#include "perinom/solvers/spectrum.hpp"

namespace perinom::detail {

std::string unstable_state(Model& model, const Loading& loading, double s, const std::vector<double>& u) {
  auto* tangent = dynamic_cast<TangentModel*>(&model);
  if (!tangent || u.size() < tangent->dofs()) return {};
  const std::size_t n = free_dofs(*tangent, loading);
  const std::size_t most = model.dofs_per_particle() == 3 ? kUnstableStateDofs3D : kUnstableStateDofs2D;
  if (n == 0 || n > most) return {};
  try {
    model.follow_loads(loading, s);
    tangent->prepare_tangent(u.data());
    const auto index = free_index(tangent->dofs(), loading);
    const Sparse T = reduce(tangent->dofs(), loading, index, static_cast<int>(n)).T;
    const Sparse K(reduced_stiffness(*tangent, TRows(T, index)));
    const Sparse sym = 0.5 * (K + Sparse(K.transpose()));
    const auto mass = model.lumped_mass();
    const Eigen::Map<const Eigen::VectorXd> m(mass.data(), static_cast<Eigen::Index>(mass.size()));
    const Sparse M = Sparse(T.transpose() * m.asDiagonal() * T);
    const PencilInertia in = pencil_inertia(sym, M, /*steps=*/1);
    if (in.negative == 0) return {};
    char text[600];
    std::snprintf(text, sizeof text,
                  "an unstable equilibrium: its stiffness gives way (x^T K x < 0) along "
                  "%ld independent direction%s (the inertia of its symmetric part over %zu free dofs), as past a "
                  "peak of the load or at buckling, or when dead loads turn with the body against supports that "
                  "cannot hold their moment (model.follower_pressure: true keeps a pressure normal to the turned "
                  "surface); ADR's damped dynamics leaves such a state, and Newton's tangent turns singular beyond it",
                  in.negative, in.negative == 1 ? "" : "s", n);
    return text;
  } catch (const std::exception&) {
    return {};
  }
}

}  // namespace perinom::detail

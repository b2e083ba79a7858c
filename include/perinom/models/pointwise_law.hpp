#pragma once
/// @file A material law over the particles of a correspondence model: P(grad u) at every
/// particle, its tangent, the stored energy, the history (trial and committed states) and the
/// fields it offers for output. The model calls it between its two operator products
/// (f = G^T (V . P(G u)) + ...), and never asks which law it holds.
///
/// Data layout: point-major arrays over the N particles, H and P N x d x d (row-major per
/// particle, H = grad u, P the first Piola-Kirchhoff stress in Pa), tangents N x d^4 with
/// C[((a d + b) d + c) d + e] = dP_ab / dH_ce, Cauchy stresses N x 3 x 3.
///
/// History: a law with history (plasticity) evaluates every particle from its committed
/// state; stresses() and energies() keep what they computed as the trial state, and
/// commit() makes the trial states the committed ones. Only the law changes its states; the
/// solvers decide when to commit (through the model). A law without history ignores commit.
///
/// The material (LinearElastic, DruckerPrager) stays a small value type that knows nothing of
/// particles; an implementation of this interface holds one, and the per-particle states.
#include <cstddef>
#include <string>
#include <vector>

namespace perinom {

class LawHistory;  // models/model_history.hpp

/// One field a law offers for output: `components` values per particle.
struct LawField {
  std::string name;
  int components = 1;
};

class PointwiseLaw {
 public:
  virtual ~PointwiseLaw() = default;
  virtual int dim() const = 0;
  /// The number of particles N.
  virtual std::size_t size() const = 0;
  /// True when the law keeps per-particle states (then commit() matters, and its tangent
  /// depends on H and on the committed state).
  virtual bool has_history() const = 0;

  /// P_i at H_i for the particles i in [begin, end), kept as their trial states. H and P are
  /// the whole N x d x d arrays; only the range is read and written. Safe to call
  /// concurrently for disjoint ranges (the model splits the particles into blocks: one call
  /// per block, not per particle, on the hot path).
  virtual void stresses(std::size_t begin, std::size_t end, const double* H, double* P) = 0;
  /// psi_i (J/m^3), the stored energy density at H_i, for the particles i in [begin, end)
  /// (H and psi the whole arrays, as for stresses; concurrent calls for disjoint ranges are
  /// safe). A law with history evaluates (and keeps) the trial states first: plastic work is
  /// dissipated, not stored. Deterministic: the model sums V_i psi_i in a fixed order.
  virtual void energies(std::size_t begin, std::size_t end, const double* H, double* psi) = 0;
  /// The consistent tangents dP/dH at H from the committed states, into C; returns the
  /// stride between particles: 0 when one d^4 block serves every particle (C then holds d^4
  /// values and H is not read), d^4 otherwise (C: N x d^4).
  virtual std::size_t tangents(const double* H, std::vector<double>& C) const = 0;
  /// The 3 x 3 Cauchy stress at H from the committed states (sigma: N x 9), nothing kept;
  /// in 2-D plane strain sigma_zz is the law's.
  virtual void cauchy(const double* H, double* sigma) const = 0;
  /// Makes the trial states the committed ones (nothing for a law without history).
  virtual void commit() = 0;
  /// The states as a load path drives them (modes, flags, checkpoints), or nullptr for a law
  /// without history.
  virtual LawHistory* history() { return nullptr; }
  /// Bytes held by the per-particle states.
  virtual std::size_t memory_bytes() const = 0;

  /// The fields the law offers for output; "stress" (the Cauchy stress, 9 components) first.
  virtual std::vector<LawField> fields() const = 0;
  /// Field `name` of fields() at H (only "stress" reads it; the others are committed
  /// states), N x components values. Throws std::invalid_argument for a name not offered.
  virtual void field(const std::string& name, const double* H, std::vector<double>& values) const = 0;
};

}  // namespace perinom

#pragma once
/// @file A law in rate form over the particles: the stress of particle i from its committed
/// state and a 3 x 3 strain increment given in the law's own frame. It knows no kinematics;
/// a kinematics wrapper (FiniteRotationLaw) turns grad u into the increment and the law's
/// stress into the first Piola-Kirchhoff stress the model needs. The Drucker-Prager points
/// implement it (and read grad u as small strain themselves when used alone).
///
/// Layout: deps, sigma 3 x 3 row-major (tension positive, in-plane and zz in plane strain),
/// D 3^4 with D[((p 3 + q) 3 + r) 3 + t] = d sigma_pq / d deps_rt.
#include <cstddef>
#include <string>
#include <vector>

#include "perinom/models/pointwise_law.hpp"

namespace perinom {

class IncrementalLaw {
 public:
  virtual ~IncrementalLaw() = default;
  virtual std::size_t size() const = 0;
  /// Evaluates particle i from its committed state by the increment deps, by the current
  /// mode of its history (an unflagged particle under loading-balance-correction answers
  /// with the elastic trial), keeps the result as its trial state and writes its stress.
  /// Safe to call concurrently for distinct i.
  virtual void update(std::size_t i, const double* deps, double* sigma) = 0;
  /// The stress of the return map from the committed state by deps, nothing kept.
  virtual void evaluate(std::size_t i, const double* deps, double* sigma) const = 0;
  /// evaluate()'s stress and its consistent tangent D (the elastic one for an elastic step).
  virtual void tangent(std::size_t i, const double* deps, double* sigma, double* D) const = 0;
  /// The stored energy density (J/m^3) of particle i's kept trial state.
  virtual double stored_energy(std::size_t i) const = 0;
  /// Makes the trial states the committed ones.
  virtual void commit() = 0;
  /// The committed states as a load path drives them, or nullptr.
  virtual LawHistory* history() = 0;
  /// The fields of the committed states (no stress: the wrapper makes that), and one of
  /// them, N x components values; throws std::invalid_argument for a name not offered.
  virtual std::vector<LawField> state_fields() const = 0;
  virtual void state_field(const std::string& name, std::vector<double>& values) const = 0;
  virtual std::size_t memory_bytes() const = 0;
};

}  // namespace perinom

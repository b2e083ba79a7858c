#pragma once
/// @file The Drucker-Prager state of every particle of a correspondence model, and the
/// rules by which the solvers evaluate and commit it (THEORY sec. 8-9).
///
/// The model hands this class grad u at a particle; it turns it into the small strain
/// (plane strain in 2-D: eps_zz = 0, sigma_zz kept), evaluates the law from the committed
/// state, and keeps the result as the particle's trial state. Plastic variables change only
/// at commit(): how a solve evaluates is the mode:
///   lbc:        unflagged particles answer with the elastic trial from their committed
///               state, flagged ones with the return map (the balance of THEORY sec. 8);
///   return_map: every particle answers with the return map from its committed state
///               (Newton on a load step, and the plain explicit scheme that commits after
///               every iteration).
#include <cstdint>
#include <vector>

#include "perinom/materials/drucker_prager.hpp"

namespace perinom {

enum class PlasticMode { lbc, return_map };

class PlasticPoints {
 public:
  /// One particle's state: the law's state and the total strain it belongs to.
  struct Point {
    DruckerPrager::State law;
    double eps[9] = {};  ///< total strain, tension positive
  };

  PlasticPoints() = default;
  PlasticPoints(const DruckerPrager& law, int dim, std::size_t particles);

  const DruckerPrager& law() const { return law_; }
  std::size_t size() const { return committed_.size(); }
  void set_mode(PlasticMode m) { mode_ = m; }
  PlasticMode mode() const { return mode_; }

  /// Evaluates particle i at grad u = H (d x d) by the current mode, keeps the trial
  /// state, and writes the d x d stress P. Safe to call concurrently for distinct i.
  void stress(std::size_t i, const double* H, double* P);
  /// The state particle i would take at H under the return map, without keeping it.
  Point evaluate(std::size_t i, const double* H) const;
  /// The consistent tangent dP/dH (d^4 values) of the return map at H, from the committed
  /// state (the elastic C for an elastic step, as in Newton on a load step).
  void tangent(std::size_t i, const double* H, double* C) const;
  /// psi = 1/2 sigma : (eps - eps_p) of the kept trial state (J/m^3).
  double stored_energy(std::size_t i) const;

  /// LBC correction: flags every unflagged particle whose kept trial violates the yield
  /// condition, f > tolerance * (A I1 + B) m (a relative tolerance on the yield stress).
  /// Returns how many were flagged now.
  std::size_t flag_violations(double tolerance);
  /// Makes the kept trial states the committed ones.
  void commit();
  /// The flagged particles.
  std::size_t flagged() const;
  /// Back to the virgin state: no stress, no plastic strain, no flag.
  void reset();

  const std::vector<Point>& committed() const { return committed_; }
  const std::vector<Point>& trial() const { return trial_; }
  const std::vector<std::uint8_t>& flags() const { return flagged_; }
  std::size_t memory_bytes() const;

 private:
  /// The 3 x 3 strain of grad u (d x d); in 2-D plane strain.
  void strain(const double* H, double* eps) const;
  /// The d x d block of a 3 x 3 tensor.
  void in_plane(const double* t3, double* t) const;

  DruckerPrager law_;
  int dim_ = 3;
  PlasticMode mode_ = PlasticMode::lbc;
  std::vector<Point> committed_, trial_;
  std::vector<std::uint8_t> flagged_;
};

}  // namespace perinom

#pragma once
/// @file The Drucker-Prager state of every particle of a correspondence model, and the
/// rules by which the solvers evaluate and commit it (THEORY sec. 8-9).
///
/// The model hands this class grad u at a particle; it turns it into the small strain
/// (plane strain in 2-D: eps_zz = 0, sigma_zz kept), evaluates the law from the committed
/// state, and keeps the result as the particle's trial state. Under finite rotation a
/// FiniteRotationLaw wraps the points and drives them by strain increments instead
/// (IncrementalLaw); they then know nothing of grad u. Plastic variables change only
/// at commit(): how a solve evaluates is the mode:
///   lbc:        unflagged particles answer with the elastic trial from their committed
///               state, flagged ones with the return map (the balance of THEORY sec. 8);
///   return_map: every particle answers with the return map from its committed state
///               (Newton on a load step, and the plain explicit scheme that commits after
///               every iteration).
/// Through PointwiseLaw the model sees the batch calls (stresses, energies, tangents, cauchy,
/// commit, fields); the load path reaches the mode, the LBC flags and the checkpointed states
/// through the per-particle calls below.
#include <cstdint>
#include <vector>

#include "perinom/materials/drucker_prager.hpp"
#include "perinom/models/incremental_law.hpp"
#include "perinom/models/model_history.hpp"
#include "perinom/models/per_particle_law.hpp"
#include "perinom/models/pointwise_law.hpp"

namespace perinom {

enum class PlasticMode { lbc, return_map };

class PlasticPoints final : public PerParticleLaw<PlasticPoints>, public IncrementalLaw, public LawHistory {
 public:
  /// One particle's state: the law's state and the total strain it belongs to.
  struct Point {
    DruckerPrager::State law;  ///< under finite rotation: the unrotated stress and plastic strain
    /// The total strain, tension positive (driven by increments: their sum).
    double eps[9] = {};
  };

  PlasticPoints() = default;
  PlasticPoints(const DruckerPrager& law, int dim, std::size_t particles);

  const DruckerPrager& law() const { return law_; }
  std::size_t size() const override { return committed_.size(); }
  int dim() const override { return dim_; }
  bool has_history() const override { return true; }

  // PointwiseLaw: the batch calls (PerParticleLaw) run stress(), stored_energy(), tangent()
  // and cauchy() below over the particles.
  using PerParticleLaw::cauchy;
  using PerParticleLaw::tangents;
  /// "stress"; "eq_plastic_strain" (xi), "plastic_strain" (3 x 3), "yielded" (1 where
  /// xi > 0), "lbc_flagged" (1 where the LBC correction flagged the particle), all committed.
  std::vector<LawField> fields() const override;
  void field(const std::string& name, const double* H, std::vector<double>& values) const override;
  void set_mode(PlasticMode m) { mode_ = m; }
  PlasticMode mode() const { return mode_; }

  /// Evaluates particle i at grad u = H (d x d) by the current mode, keeps the trial
  /// state, and writes the d x d stress P. Safe to call concurrently for distinct i.
  void stress(std::size_t i, const double* H, double* P);
  /// The state particle i would take at H under the return map, without keeping it.
  Point evaluate(std::size_t i, const double* H) const;
  /// The 3 x 3 Cauchy stress of a state, and of the return map at H (nothing kept).
  void cauchy(const Point& point, double* sigma) const;
  void cauchy(std::size_t i, const double* H, double* sigma) const { cauchy(evaluate(i, H), sigma); }
  /// The consistent tangent dP/dH (d^4 values) of the return map at H, from the committed
  /// state (the elastic C for an elastic step, as in Newton on a load step).
  void tangent(std::size_t i, const double* H, double* C) const;
  /// psi = 1/2 sigma : (eps - eps_p) of the kept trial state (J/m^3).
  double stored_energy(std::size_t i) const override;

  // IncrementalLaw: the same states driven by 3 x 3 strain increments (by the mode).
  void update(std::size_t i, const double* deps, double* sigma) override;
  void evaluate(std::size_t i, const double* deps, double* sigma) const override;
  void tangent(std::size_t i, const double* deps, double* sigma, double* D) const override;
  /// "eq_plastic_strain" (xi), "plastic_strain" (3 x 3), "yielded" (1 where xi > 0),
  /// "lbc_flagged" (1 where the LBC correction flagged the particle), all committed.
  std::vector<LawField> state_fields() const override;
  void state_field(const std::string& name, std::vector<double>& values) const override;

  /// LBC correction: flags every unflagged particle whose kept trial violates the yield
  /// condition, f > tolerance * (A I1 + B) m (a relative tolerance on the yield stress).
  /// Returns how many were flagged now.
  std::size_t flag_violations(double tolerance) override;

  // LawHistory (plastic_history.cpp): flagged = PlasticMode::lbc; a checkpoint holds per
  // particle sigma (9), eps_p (9), xi and eps (9), and the flags.
  LawHistory* history() override { return this; }
  void set_history_mode(HistoryMode mode) override;
  std::vector<double> history_variable() const override;
  std::size_t values_per_particle() const override { return 28; }
  HistoryState save_history() const override;
  void restore_history(const HistoryState& state) override;
  void reset_history() override { reset(); }
  /// Makes the kept trial states the committed ones.
  void commit() override;
  /// Each committed state's secant shear stiffness over the elastic one, |dev sigma| / (2 G
  /// |dev eps|) with eps the total strain, at most 1: 1 while elastic (and for no strain),
  /// falling as plastic strain accumulates under a bounded stress.
  std::vector<double> secant_ratios() const;
  /// The flagged particles.
  std::size_t flagged() const;
  /// Back to the virgin state: no stress, no plastic strain, no flag.
  void reset();
  /// Takes committed states and flags saved from committed() and flags() (a checkpoint), the
  /// trial states equal to them as after commit(). Throws std::invalid_argument for a size
  /// other than size().
  void restore(std::vector<Point> committed, std::vector<std::uint8_t> flags);

  const std::vector<Point>& committed() const { return committed_; }
  const std::vector<Point>& trial() const { return trial_; }
  const std::vector<std::uint8_t>& flags() const { return flagged_; }
  std::size_t memory_bytes() const override;

 private:
  /// The 3 x 3 strain of grad u (d x d); in 2-D plane strain.
  void strain(const double* H, double* eps) const;
  /// The d x d block of a 3 x 3 tensor.
  void in_plane(const double* t3, double* t) const;
  /// The law's increment from committed state n to grad u = H: the total strain goes to
  /// out.eps, its change to deps.
  void increment(const Point& n, const double* H, Point& out, double* deps) const;
  /// The law's part of particle i's trial state t by deps, by the mode.
  void advance(std::size_t i, const double* deps, Point& t) const;

  DruckerPrager law_;
  int dim_ = 3;
  PlasticMode mode_ = PlasticMode::lbc;
  std::vector<Point> committed_, trial_;
  std::vector<std::uint8_t> flagged_;
};

}  // namespace perinom

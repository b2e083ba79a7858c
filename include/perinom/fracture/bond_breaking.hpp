#pragma once
/// @file Bond breaking during a run (issue 17, THEORY sec. 10): at a state u of a
/// correspondence model, the bonds a criterion selects, then broken in the model's graph
/// (CorrespondenceModel::break_bonds: the touched rows of G and S refreshed, particles whose
/// family no longer spans R^d detached). Irreversible.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "perinom/fracture/criteria.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/models/correspondence.hpp"

namespace perinom {
namespace detail {
class RowScreen;
}

enum class DamageCriterion {
  instability,  ///< seed 002 sec. 4: hourglass strain above its value when the largest stretch reached s_max
  stretch,      ///< bond stretch above s_c
  stress,       ///< (sigma1_i + sigma1_j) / 2 above f_t (seed 000 eq. 49-51)
};

/// Reads "instability", "stretch" or "stress"; false for any other name.
bool parse_damage_criterion(const std::string& name, DamageCriterion& c);

class BondBreaking {
 public:
  /// `parameter` is s_max, s_c or f_t (Pa) for the criterion. The model and cloud must outlive
  /// this object. Throws std::invalid_argument unless parameter > 0.
  BondBreaking(CorrespondenceModel& model, const PointCloud& cloud, DamageCriterion criterion, double parameter);
  ~BondBreaking();

  /// A no-fail zone (the peers' device at grips and impact points): bonds with an end at one
  /// of these particles never break, and the instability criterion neither arms on their
  /// stretch nor takes s_hg_max from them. Adds to the zones given before.
  void hold(const std::vector<ParticleId>& particles);

  /// The bonds due at u (N x d), kept for apply(); returns how many (a bond found in both
  /// directions counts twice here, once in apply()). With softening bonds
  /// (CorrespondenceModel::soften_broken_bonds) it first commits their openings at u: u is a
  /// state the run keeps (a load path's balance). H: grad u at u when the caller has it
  /// (CorrespondenceModel::last_gradient() right after the force at u), else nullptr and the
  /// instability and stress criteria take it from G. With softening bonds the stress
  /// criterion keeps a bond over f_t only if it is opened to its law's peak
  /// (CohesiveBonds::at_peak) or both its particles have such a bond over f_t.
  std::size_t find(const double* u, const double* H = nullptr);
  /// The bonds the last find() kept (row order), until apply().
  const std::vector<BondPair>& due() const { return due_; }
  /// The stretch and instability criteria read only the rows that can hold a bond at their
  /// threshold (lib/fracture/row_screen.hpp: a bound from a snapshot, taken anew when the rows
  /// it keeps pass an eighth of all; every row for a while after snapshots that last fewer
  /// than 16 calls): the same bonds as a pass over every row, which `false` restores (for
  /// checks and benchmarks). On by default.
  void screen(bool on);
  /// Breaks the bonds find() kept; returns the bonds that died (pairs, once each).
  std::size_t apply();
  /// The same at a state u whose internal force f the caller holds: f becomes the changed
  /// model's force at u, updated on the refreshed rows (CorrespondenceModel::break_bonds);
  /// also the strain energy released at u. Returns the bonds that died, and that energy.
  BondBreaks apply(const double* u, double* f);

  /// The model's stable time step now, 2 / sqrt(max_i sum_j |K_ij| / m_i) (Gershgorin, as
  /// solve_verlet's): the first call sums every stiffness row; after that each apply() sums
  /// anew only the rows its breaks change (the refreshed rows and their families).
  double stable_time_step();
  /// The stiffness row sums per dof behind stable_time_step() (empty before its first call).
  const std::vector<double>& row_sums() const { return row_sums_; }

  /// Bonds broken so far by apply() (pairs).
  std::size_t broken() const { return broken_; }
  /// Particles detached so far.
  std::size_t detached() const { return detached_; }
  /// The instability criterion's s_hg_max once armed (0 otherwise, and for other criteria).
  double hourglass_threshold() const { return instability_ ? instability_->threshold() : 0.0; }
  /// The instability criterion: the find() call (counted from 1) that armed it, or -1.
  std::int64_t armed_at_find() const { return armed_find_; }

  /// What a run needs to go on from here (a checkpoint): the counts, the criterion's state
  /// and the bonds each apply() broke, as numbers (particle indices are exact in a double).
  std::vector<double> state() const;
  /// Puts this object and its model, both as built (no bond broken yet), into a state()
  /// taken from the same scene: each apply()'s bonds broken again, in the same groups and
  /// order (a stored stabilization is updated in place, so the same sequence of breaks is
  /// what gives the same bits), with the stiffness row sums summed before them and kept
  /// through them, as a run that asked for stable_time_step() before breaking keeps them
  /// (Verlet and load paths do). Throws std::invalid_argument for a state that does not fit.
  void restore(const std::vector<double>& state);

 private:
  CorrespondenceModel* model_;
  const PointCloud* cloud_;
  DamageCriterion criterion_;
  double parameter_;
  std::optional<InstabilityCriterion> instability_;
  std::vector<BondPair> due_;
  std::vector<char> held_;  // per particle: in a no-fail zone (empty: none)
  std::vector<double> row_sums_, mass_;  // per dof, once stable_time_step() has been asked
  double w2_ = 0.0;                      // max_k row_sums_[k] / mass_[k], at dof w2_at_
  std::size_t w2_at_ = 0;
  void largest_ratio();
  std::vector<double> H_, sigma_, sigma1_;  // workspaces: grad u, stresses, sigma1
  std::vector<char> cracking_;               // workspace: a particle with a bond due and at its law's peak
  std::unique_ptr<detail::RowScreen> screen_;  // null: every row is read
  int screened_measure_ = 0;                  // what the screen's snapshot measures (0: none)
  int since_snapshot_ = 0, skip_ = 0, backoff_ = 0;  // calls: since the snapshot, left unscreened, last backoff
  std::vector<ParticleId> rows_, all_rows_;    // the rows kept; every row
  template <class Squared>
  const std::vector<ParticleId>& rows_near(int measure, const Squared& squared, const double* u, const double* H,
                                           double level);
  /// After break_bonds: the counts, and the stiffness rows the breaks changed summed anew.
  std::size_t account(const BondBreaks& b);
  std::vector<BondPair> died_;       // every bond apply() broke, in order
  std::vector<std::size_t> groups_;  // how many of them each apply() broke
  std::size_t broken_ = 0, detached_ = 0;
  std::int64_t finds_ = 0, armed_find_ = -1;
};

}  // namespace perinom

#pragma once
/// @file Boundary conditions reduced to what a solver applies: fixed degrees of freedom
/// with prescribed values, and an external force vector, both at full load.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "perinom/core/types.hpp"

namespace perinom {

/// What a loading spread over MPI ranks needs of them (issue 19; lib/distributed): a rank's
/// loading holds the constraints of its owned dofs (the first owned_dofs() of its local part's
/// numbering), and their couplings read the part's ghost dofs too (indices from owned_dofs() on).
/// Every call is collective: each rank makes the same calls in the same order.
class LoadingRanks {
 public:
  virtual ~LoadingRanks() = default;
  virtual std::size_t owned_dofs() const = 0;
  /// The local part's values at the owned values u: u's, then the ghosts' from their owners.
  virtual const double* with_ghosts(const double* u) const = 0;
  /// Scratch over the local part's dofs, zeroed; add_ghosts_to_owners() adds its ghost
  /// entries into their owners' owned entries on the other ranks.
  virtual double* zeroed_scratch() const = 0;
  virtual void add_ghosts_to_owners() const = 0;
  virtual double max(double v) const = 0;
};

/// A load at factor s in [0, 1] applies force0 + s (force - force0) and prescribes, for each
/// constrained degree of freedom k, with the target t_k = value0[k] + s * value[k], either
/// u[fixed[k]] = t_k (the particle itself: the seed's
/// "outer layer" condition), or, when the constraint has couplings, the value at a point
/// off the particle through its first-order reconstruction u_i + (grad u)_i . d = s * value
/// (a face-located condition). The latter reads
///   u[fixed[k]] = scale[k] * (t_k - sum_c coef[c] u[coupled[c]]),
/// c over couplings[k] .. couplings[k+1).
struct Loading {
  std::vector<std::int64_t> fixed;  ///< degree-of-freedom indices (i*dofs_per_particle + a)
  std::vector<double> value;        ///< prescribed displacement at full load (m)
  /// Prescribed velocities (m/s), parallel to `fixed`, or empty: constraint k's target grows
  /// by rate[k] t with the time t of a dynamic run (Verlet; with a ramp time, the ramped time
  /// the solver passes: the integral of the load factor).
  std::vector<double> rate;
  std::vector<double> force;        ///< external force at full load (N), one per dof
  // Couplings of face-located constraints (empty when every constraint is on its particle).
  std::vector<Offset> couplings;    ///< CSR offsets, fixed.size() + 1 entries
  std::vector<std::int64_t> coupled;
  std::vector<double> coef, scale;
  /// Face-located constraints in collocation rather than Galerkin form: the constrained dof's
  /// own row holds the constraint and its reaction stays on that particle (reduce is then
  /// zero_fixed, and StaticSystem adds no multipliers). The improved and strong formulations,
  /// collocation schemes near the surface themselves, use it: their patch tests are exact
  /// with it and not with the Galerkin form.
  bool collocated = false;
  /// For each coupling: the constraint on its dof, or -1 for a free dof (index_couplings).
  std::vector<std::int64_t> coupled_constraint;
  /// Set on a rank's part of a distributed loading with face-located constraints (couplings
  /// then sized on every rank, a rank without any included): impose, reduce, reactions and
  /// multipliers exchange with the other ranks through it. Null: one process.
  const LoadingRanks* ranks = nullptr;
  // Where a load stage starts (begin_stage); empty: from zero.
  std::vector<double> value0;  ///< the constrained values at s = 0 (m)
  std::vector<double> force0;  ///< the external force at s = 0 (N)
  /// The part of `force` (and of force0) that pressures make, per dof, in the reference
  /// configuration: a model with follower pressures turns it with the surface (empty: none).
  std::vector<double> pressure_force, pressure_force0;
  /// Supports, for reactions: the support each constraint belongs to (an index into
  /// support_names, parallel to `fixed`; -1 for none), e.g. the boundary item that set it.
  /// Empty when the loading records none.
  std::vector<int> support;
  std::vector<std::string> support_names;

  /// The external force on dof k at factor s.
  double force_at(double s, std::size_t k) const {
    const double f0 = force0.empty() ? 0.0 : force0[k];
    return f0 + s * ((force.empty() ? 0.0 : force[k]) - f0);
  }
  bool has_force() const { return !force.empty() || !force0.empty(); }
  /// The pressures' share of force_at(s, k).
  double pressure_force_at(double s, std::size_t k) const {
    const double f0 = pressure_force0.empty() ? 0.0 : pressure_force0[k];
    return f0 + s * ((pressure_force.empty() ? 0.0 : pressure_force[k]) - f0);
  }
  bool has_pressure() const { return !pressure_force.empty() || !pressure_force0.empty(); }
  /// |external force at s|.
  double force_norm(double s) const;
  /// The prescribed value of constraint k at factor s (and time t, for velocities).
  double target(double s, std::size_t k, double t = 0.0) const {
    return (value0.empty() ? 0.0 : value0[k]) + s * value[k] + (rate.empty() ? 0.0 : rate[k] * t);
  }
  bool has_rates() const {
    for (const double r : rate)
      if (r != 0.0) return true;
    return false;
  }
  /// Makes this loading start where the body is: value0 from u (the constrained values, or
  /// their face reconstructions) and force0 from the previous stage's full force (none for
  /// the first stage). Values and forces of this stage then act as increments and totals.
  /// Over ranks (`ranks` set) u is the owned dofs; a face constraint's ghost dofs are read
  /// from their owners (every rank calls it).
  void begin_stage(const Loading* previous, const double* u);

  /// Adds a constraint, replacing an earlier one on the same dof (and its support), with a
  /// prescribed velocity v_rate (m/s) on top of the displacement v.
  void fix(std::int64_t dof, double v, int support_index = -1, double v_rate = 0.0);
  /// Registers a support by name (returns its index for fix), or finds it if known.
  int add_support(const std::string& name);
  bool has_supports() const { return !support_names.empty(); }
  /// The reaction of every support at factor s, from the internal force fint at the state:
  /// R[g * dpp + a] = sum of fint - f_ext(s) over the constrained dofs of support g with
  /// component a (dof % dpp), the force (N) the support exerts on the body (Galerkin
  /// face-located supports: the sum of their multipliers, the reaction spread over the dofs
  /// their constraints read, which the dofs' own fint - f_ext do not see); dpp is the model's
  /// dofs per particle. At equilibrium, sum_g R_g + the sum of the applied loads = 0 up to
  /// the residual on the free dofs (for models whose internal forces sum to zero).
  /// R holds support_names.size() * dpp values; nothing is allocated.
  void reactions(const double* fint, double s, int dpp, double* R) const;
  /// Galerkin supports: the multipliers at a state (fint its internal force), one per
  /// constraint, the force (N) each constraint exerts in total (its reaction spread over the
  /// dofs its row reads). out holds fixed.size() values; nothing is allocated.
  void multipliers(const double* fint, double s, double* out) const;
  /// Column names in the order of reactions(): "NAME.Rx", "NAME.Ry" (, "NAME.Rz") for dpp 2
  /// or 3, "NAME.R" for one dof per particle (a plate's transverse force).
  std::vector<std::string> reaction_columns(int dpp) const;
  /// Sets u at the constrained dofs (at time t for velocities). Face-located constraints are
  /// solved for the constrained values given the free ones (Gauss-Seidel sweeps to rounding:
  /// the constraints of one face read each other), so E u = t holds after every call.
  /// Throws SolveError, naming a constraint, when 200 sweeps (or rounds over ranks) do not
  /// converge; reduce, reactions and multipliers do the same for the multipliers.
  void impose(double s, double* u, double t = 0.0) const;
  /// Zeros the constrained entries of r (a residual or a velocity).
  void zero_fixed(double* r) const;
  /// The Galerkin reduction of a force (or residual) r onto the free dofs: with the
  /// constraints written E u = t (row k: 1/scale_k on its own dof, coef on the coupled ones),
  /// the multipliers lambda solving (E_FF)^T lambda = -r_F carry the constrained dofs' force
  /// to the free ones, r_R += (E_FR)^T lambda, and r_F = 0. So a face-located constraint
  /// reacts on every particle its reconstruction reads, as the trace of a facet load does,
  /// and the reduced stiffness is T^T K T (symmetric when K is). Without couplings it is
  /// zero_fixed. Needs index_couplings after the couplings change; allocates nothing.
  void reduce(double* r) const;
  /// Fills coupled_constraint and the scratch reduce needs.
  void index_couplings();
  bool coupled_constraints() const { return !couplings.empty(); }
  /// Face-located constraints in the Galerkin form (multipliers, reduce).
  bool galerkin() const { return coupled_constraints() && !collocated; }

 private:
  /// lambda_ from (E_FF)^T lambda = -r_F, r_at(dof) giving r (a force, f_ext - f_int).
  /// (A template, defined and instantiated in loading.cpp only: a std::function would
  /// allocate for the capturing lambdas of the hot paths.)
  template <class RAt>
  void solve_multipliers(const RAt& r_at) const;
  /// Throws SolveError: `what`'s sweeps did not converge, constraint k changing most.
  [[noreturn]] void not_converged(const char* what, std::size_t k) const;
  mutable std::vector<double> lambda_, sum_, remote_;  // scratch of reduce and reactions
};

/// Throws InputError, naming the field and the entry, unless `loading` fits a model of `dofs`
/// degrees of freedom: every fixed dof below dofs, value (and rate, value0, support, scale when
/// given) one entry per fixed dof, force, force0 and the pressure forces empty or dofs entries,
/// and the couplings a CSR over the constraints (their dofs below dofs in one process). Values
/// are not read: a NaN load is the solvers' NaN guard's to report. O(fixed + couplings): the
/// solvers call it once, at their entry. With `with_start` false the stage's start (value0,
/// force0, pressure_force0) is not checked: a load path's begin_stage sets it anew.
void check_loading(const Loading& loading, std::size_t dofs, bool with_start = true);

/// One stage of a load path: its loading (values as increments over the stage, forces as
/// totals at its end; see begin_stage) applied in `steps` equal load steps.
struct LoadStage {
  std::string name;
  int steps = 1;
  Loading loading;
};

}  // namespace perinom

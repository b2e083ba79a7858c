#pragma once
/// @file Broken bonds that still carry a softening force (`damage.fracture_energy`, issue 18
/// item 3; THEORY sec. 10). When the stress criterion breaks a bond of a correspondence model
/// the bond leaves the operators and becomes a pair force along its direction e = xi / |xi|,
/// a bilinear function of its opening eta = e . (u_j - u_i) (small strain):
///   F(kappa) rises as F0 kappa / eta_e up to eta_e = |xi| f_t / E (the bond's elongation in a
///   body at f_t), then falls linearly to zero at eta_u; kappa is the largest opening so far,
///   and below it the bond unloads to the origin (secant); a closed bond (eta <= 0) pushes
///   back with the rising branch's stiffness, F = F0 eta / eta_e (the crack's faces in
///   contact, elastic: its energy is stored, not dissipated). Without that a particle the
///   breaks detach has nothing against closing: the 2-D bar's band collapsed sideways
///   (bonds closed by 10 eta_u, nearly a spacing), its peak fell to 0.77 f_t A and its
///   balances stalled (docs/theory.md, "Softening bonds"). The force on j is +V_i V_j F e,
///   on i its opposite.
/// The scaling is a crack-band one by the family (the bond-based energy argument of Silling
/// and Askari 2005, with the family's own sums in place of the continuum integrals): with
/// S_i = sum_j V_j |xi_ij| over i's live family, a flat crack of normal n through bulk is
/// crossed, per unit area, by bonds of weight (1/2) sum_j V_j |xi_ij . n| ~ c_d S_i / 2
/// (c_3 = 1/2, c_2 = 2/pi: the mean of |cos| over directions), carrying a traction
/// (1/2) sum_j V_j F (xi . n)^2 / |xi| ~ F S_i / (2 d). So F0 = 2 d f_t / S_ij gives the traction
/// f_t at the peak, and eta_u = 2 G_f / (d c_d f_t) makes the work of every crossing bond,
/// F0 eta_u / 2 each (the triangle's area, whatever eta_e), sum to G_f per unit area of crack
/// (S_ij = (S_i + S_j) / 2, taken when the law is set, before any break). eta_u does not
/// depend on the spacing: the dissipated energy is regularised. The stress criterion hands a
/// bond over only when it is opened to the peak (at_peak) or both its particles have such a
/// bond (BondBreaking::find); with that gate the notched beam's peaks at three spacings lie
/// within a few percent of the cohesive-crack FEM's 1.351 kN (without it 21% apart; the
/// figures: docs/verification/notched_beam.md).
/// A lattice crack along an axis is crossed by about 4% fewer bonds than the mean direction
/// (measured in tests/models/test_cohesive_bonds.cpp).
#include <cstddef>
#include <utility>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/neighbors/bond_graph.hpp"

namespace perinom {

/// The material constants of the softening law.
struct CohesiveLaw {
  double f_t = 0.0;  ///< tensile strength (Pa)
  double G_f = 0.0;  ///< fracture energy (J/m^2)
  double E = 0.0;    ///< Young's modulus (Pa)
};

/// The smallest G_f for which a bond no longer than `longest` softens: eta_u above its
/// eta_e, d c_d f_t^2 longest / (2 E). Below it the law has no softening branch.
double least_fracture_energy(int dim, const CohesiveLaw& law, double longest);

class CohesiveBonds {
 public:
  /// The family sums S_i over `graph`'s live bonds of the cloud x (N x dim) with volumes V.
  /// Throws std::invalid_argument unless f_t, G_f and E are positive and G_f is above
  /// least_fracture_energy for the graph's longest live bond.
  CohesiveBonds(int dim, const std::vector<double>& x, const std::vector<double>& volume, const BondGraph& graph,
                const CohesiveLaw& law);

  /// eta_u, the opening at which a bond carries nothing more (m).
  double opening_limit() const { return eta_u_; }

  /// Whether the pair (i, j) is opened at u to its law's peak: e . (u_j - u_i) >= eta_e =
  /// |xi| f_t / E. The stress criterion hands a bond to the law when it is, or when both its
  /// particles have such a bond (BondBreaking::find).
  bool at_peak(ParticleId i, ParticleId j, const double* u) const;

  /// Makes the pairs (i, j) (each once, i != j) softening bonds from now on, with kappa 0.
  void add(const std::vector<std::pair<ParticleId, ParticleId>>& pairs);

  /// f += the forces at u of the bonds from the `first`-th on (in the order added), each at
  /// kappa = max(committed kappa, eta); returns their stored energy at u.
  double add_force(const double* u, double* f, std::size_t first = 0) const;
  /// Their stored (recoverable) energy at u: sum V_i V_j F eta / 2 (J).
  double energy(const double* u) const;
  /// kappa = max(kappa, eta) at u for every bond: the load path's balanced states.
  void commit(const double* u);
  /// sums[r d + a] += sum over the bonds at rows[r] of V_i V_j (F0 / eta_e) sum_c |e_a e_c|, the
  /// bound of their stiffness (the rising branch's) for the explicit solvers' density;
  /// rows sorted (nullptr: every particle, r = i).
  void add_row_sums(const std::vector<ParticleId>* rows, double* sums) const;

  /// dF/deta of every bond at u (V_i V_j included) for tangent_row: the rising or softening
  /// branch's slope where eta >= kappa, the secant F(kappa) / kappa below it, F0 / eta_e when closed.
  void prepare_tangent(const double* u);
  /// Whether particle i has a softening bond.
  bool touches(ParticleId i) const;
  /// Row i of the tangent with its bonds added: cols (sorted) and blocks (blocks[(q d + a) d + b]
  /// = K_(i a),(cols[q] b), BlockRowVisitor's layout) merged with k e e^T at (i, i) and
  /// -k e e^T at (i, j) for each bond (i, j), into out_cols (sorted) and out_blocks. k is 0
  /// until prepare_tangent, and the columns do not depend on u (a symbolic pattern stays).
  void tangent_row(ParticleId i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks,
                   std::vector<ParticleId>& out_cols, std::vector<double>& out_blocks) const;

  /// The committed openings kappa, in the order the bonds were added (a checkpoint's), and
  /// their restoration on the same bonds added again in that order (throws
  /// std::invalid_argument unless there is one finite, non-negative value per bond).
  std::vector<double> kappas() const;
  void restore_kappas(const std::vector<double>& kappa);

  /// The number of softening bonds, and of those spent (kappa >= eta_u: they carry nothing).
  std::size_t size() const { return bonds_.size(); }
  std::size_t spent() const;
  /// The energy the bonds dissipated up to their committed kappa (J).
  double dissipated() const;
  std::size_t memory_bytes() const { return bonds_.capacity() * sizeof(Bond); }

 private:
  struct Bond {
    ParticleId i, j;
    double e[3];
    double F0;     // V_i V_j 2 d f_t / S_ij (N)
    double eta_e;  // the peak's opening (m)
    double kappa;  // the largest committed opening (m)
  };
  int dim_;
  std::vector<double> x_, volume_, S_;
  CohesiveLaw law_;
  double eta_u_ = 0.0;
  std::vector<Bond> bonds_;
  std::vector<double> slope_;  // dF/deta at the last prepare_tangent, by bond
  // The bonds of each particle (CSR over particles, bond indices), built when bonds are added.
  std::vector<std::size_t> at_ptr_, at_bond_;
  double opening(const Bond& b, const double* u) const;
  /// The envelope: the force at the largest opening kappa.
  double envelope(const Bond& b, double kappa) const;
  /// The force at opening eta (committed kappa and eta).
  double force(const Bond& b, double eta) const;
};

}  // namespace perinom

#pragma once
/// @file One interface for the stabilization S of the correspondence force, at three assembly
/// levels (in the spirit of MFEM's AssemblyLevel): how S is stored is the level's business,
/// what S is (THEORY sec. 4 and 6) is the same at every level.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "perinom/geometry/point_cloud.hpp"
#include "perinom/operators/bond_weights.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
#include "perinom/operators/row_accumulator.hpp"
#include "perinom/operators/scalar_csr.hpp"

namespace perinom {

/// fused: inside the products of G (FusedStabilization: one value per bond, the fastest;
///        needs symmetric families, i.e. a horizon radius);
/// assembled: S0 stored once (about 75 bytes per bond in 3-D);
/// matrix_free: two extra bond passes (Stabilization: 16 bytes per bond, the slowest).
enum class AssemblyLevel { fused, assembled, matrix_free };

/// S (x) I_d applied to a displacement field u (N x d) of G's particles. Every level writes
/// S u = G^T(-B) + rest(u) for a tensor field B (N x d x d) and a remainder, so that a force
/// f = G^T(V . P) + S u costs one transposed product: the model subtracts B from V . P.
///   gradient(u, H)      H = grad u (G.apply; the fused level gets its Laplacian in that pass)
///   tensor_part(u, H)   B, or nullptr when the level has none (assembled)
///   add_rest(u, H, f)   f += rest(u)
/// The three calls go in that order for one u. Rows of S0 (tangents) come from add_row at
/// every level. Each level owns its workspaces; nothing writes into G.
class StabilizationTerm {
 public:
  virtual ~StabilizationTerm() = default;
  StabilizationTerm(const StabilizationTerm&) = delete;
  StabilizationTerm& operator=(const StabilizationTerm&) = delete;

  virtual AssemblyLevel level() const = 0;
  virtual void gradient(const double* u, double* H);
  virtual const double* tensor_part(const double* u, const double* H) = 0;
  virtual void add_rest(const double* u, const double* H, double* f) = 0;
  /// Su = S u (H: workspace of N x d x d, left holding grad u).
  void apply(const double* u, double* H, double* Su);
  /// Adds row i of S0 to acc: the value to acc.at(j)[k * (copies + 1)] for k < copies (1 for
  /// the scalar S0, d for the diagonal of d x d blocks).
  virtual void add_row(std::size_t i, RowAccumulator& acc, int copies) const = 0;
  /// After G.refresh_rows(rows) (distinct rows, from BondGraph::rows_touched): S as built from
  /// the live bonds. Throws std::logic_error for a stored S without the operator it came from.
  virtual void refresh_rows(const std::vector<ParticleId>& rows) = 0;
  /// The same around the change itself: change() breaks bonds in G's graph and calls
  /// G.refresh_rows(rows) (rows: BondGraph::rows_touched of those breaks, taken before them).
  /// A level that updates S by differences (assembled: S0 minus the blocks of those centres
  /// before the change, plus their blocks after) reads G and the graph before change(); the
  /// others call it first and refresh as above.
  virtual void refresh_rows(const std::vector<ParticleId>& rows, const std::function<void()>& change);
  /// False for a stored S without its source, whose refresh_rows throws.
  virtual bool refreshable() const { return true; }
  /// Scales each centre's block (c_i = factor_i times its built value; Stabilization::
  /// set_centre_factors). The matrix-free levels only: a stored or fused S sums the centres'
  /// blocks into one value per entry or bond, and throws std::logic_error.
  virtual void set_centre_factors(std::vector<double> factor);
  /// For memory listings: what is stored, and its bytes (workspaces included).
  virtual std::string name() const = 0;
  virtual std::size_t memory_bytes() const = 0;
  /// The stored S0 (assembled level), or nullptr.
  virtual const ScalarCsr* stored() const { return nullptr; }

 protected:
  explicit StabilizationTerm(const NonlocalOperator& G) : G_(&G) {}
  const NonlocalOperator* G_;
};

/// The first-order S0 of G (a first-order operator from a fit; c_i = modulus / tr K_i,
/// modulus = C_hg 2 mu) at the given level. G must outlive the term. Throws InputError
/// naming model.stabilization_storage when the level is fused and the families are not
/// symmetric.
std::unique_ptr<StabilizationTerm> make_stabilization(const PointCloud& cloud, const NonlocalOperator& G,
                                                      double modulus, AssemblyLevel level);

/// The stabilization of G's fit order at the given level. Order 1 as above (weights unused).
/// Order 2: the operator energy of the second-order fit (seed 002 eq. 35-39) on each
/// component, from the fit with its Hessian on G's graph and `weights`, scaled by the
/// first-order c_i = modulus / tr K_i: matrix_free keeps that fit (refreshable; its d +
/// d(d+1)/2 weights per bond in both orders); assembled stores S and drops the fit (no
/// refresh); fused
/// rests on first-order identities and throws InputError naming model.stabilization_storage.
std::unique_ptr<StabilizationTerm> make_stabilization(const PointCloud& cloud, const NonlocalOperator& G,
                                                      const BondWeights& weights, double modulus, AssemblyLevel level);

/// Adds row i of a stored S0 to acc as StabilizationTerm::add_row does (copies values per
/// column on the block diagonal).
void add_stored_row(const ScalarCsr& S0, std::size_t i, RowAccumulator& acc, int copies);

/// An S assembled elsewhere (the second-order operator energy, or S0 of an operator G was
/// corrected from), applied to each of G's d components: the assembled level without the
/// operator S came from, so refresh_rows throws. `name` labels it in memory listings.
std::unique_ptr<StabilizationTerm> stored_stabilization(const NonlocalOperator& G, ScalarCsr S, std::string name);

}  // namespace perinom

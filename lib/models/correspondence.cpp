#include "perinom/models/correspondence.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "perinom/core/error.hpp"
#include "perinom/core/parallel.hpp"
#include "perinom/models/elastic_points.hpp"
#include "perinom/operators/bond_weights.hpp"
#include "perinom/operators/stabilization.hpp"
#include "perinom/operators/tangent_rows.hpp"

namespace perinom {
namespace {

// The pointwise law is called once per block of this many particles, in parallel: one
// virtual call per block, and the block's P still in cache when the model scales it.
constexpr std::size_t law_block = 256;

template <class Body>
void for_each_law_block(std::size_t n, Body&& body) {
  const std::size_t blocks = (n + law_block - 1) / law_block;
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < blocks; ++b) body(b * law_block, std::min(n, (b + 1) * law_block));
}

}  // namespace

bool parse_formulation(const std::string& name, Formulation& f) {
  if (name == "classical") f = Formulation::classical;
  else if (name == "improved") f = Formulation::improved;
  else if (name == "strong") f = Formulation::strong;
  else if (name == "consistent") f = Formulation::consistent;
  else return false;
  return true;
}

bool parse_stabilization_storage(const std::string& name, StabilizationStorage& s) {
  if (name == "auto") s = StabilizationStorage::automatic;
  else if (name == "fused") s = StabilizationStorage::fused;
  else if (name == "assembled") s = StabilizationStorage::assembled;
  else if (name == "matrix_free") s = StabilizationStorage::matrix_free;
  else return false;
  return true;
}

CorrespondenceModel::CorrespondenceModel(const PointCloud& cloud, const Families& families,
                                         const LinearElastic& material,
                                         const CorrespondenceOptions& options, Surface surface,
                                         BoundaryFacets facets, std::unique_ptr<PointwiseLaw> law)
    : dim_(cloud.dim),
      order_(options.operator_order),
      formulation_(options.formulation),
      material_(material),
      surface_(std::move(surface)),
      volume_(cloud.volume),
      law_(std::move(law)) {
  // Once, before anything indexes the cloud by the families or the material by the dimension.
  check_cloud(cloud);
  check_families(families, cloud.size());
  check_material(material);
  if (material.dim != cloud.dim)
    throw InputError("CorrespondenceModel: LinearElastic::dim = " + std::to_string(material.dim) + " on a " +
                     std::to_string(cloud.dim) + "-D cloud");
  if (!(options.stabilization >= 0.0 && std::isfinite(options.stabilization))) {
    char text[120];
    std::snprintf(text, sizeof text, "CorrespondenceOptions::stabilization = %g: must be zero or positive",
                  options.stabilization);
    throw InputError(text);
  }
  c_hg_ = options.stabilization;
  fracture_fields_ = options.fracture_fields;
  x_ = cloud.x;
  const bool consistent = formulation_ == Formulation::consistent;
  if (consistent && facets.empty())
    throw std::invalid_argument("CorrespondenceModel: the consistent formulation needs the boundary facets");
  if (!consistent && formulation_ != Formulation::classical && surface_.in_band.size() != cloud.size())
    throw std::invalid_argument("CorrespondenceModel: the improved and strong formulations need surface data");
  if (formulation_ == Formulation::classical || consistent) surface_ = Surface{};
  // At order 2 the matrix-free S keeps a fit of its own (the uncorrected one, as assembled:
  // the cantilever's tip agrees to 2e-14), so only the first-order forms need G's identities.
  if (consistent && order_ == 1 && options.stabilization_storage != StabilizationStorage::automatic &&
      options.stabilization_storage != StabilizationStorage::assembled)
    throw InputError("model.stabilization_storage: the consistent formulation with operator_order 1 stores S "
                     "assembled (its corrected G has not the first-order identities the fused and matrix-free "
                     "forms rest on); use auto or assembled");
  secant_ = options.secant_stabilization && options.stabilization > 0.0;
  if (secant_ && !options.plasticity)
    throw std::invalid_argument("CorrespondenceModel: a secant stabilization follows a plastic law");
  if (secant_ && consistent && order_ == 1)
    throw InputError("model.stabilization_scale: secant needs a matrix-free stabilization, which the consistent "
                     "formulation has at operator_order 2 only");
  if (secant_ && options.stabilization_storage != StabilizationStorage::automatic &&
      options.stabilization_storage != StabilizationStorage::matrix_free)
    throw InputError("model.stabilization_scale: secant scales each family's block of S, which only the "
                     "matrix-free storage keeps apart; use stabilization_storage auto or matrix_free");
  if (law_ && (law_->dim() != dim_ || law_->size() != cloud.size()))
    throw std::invalid_argument("CorrespondenceModel: a law for " + std::to_string(law_->size()) + " particles in " +
                                std::to_string(law_->dim()) + "-D on a cloud of " + std::to_string(cloud.size()) +
                                " in " + std::to_string(dim_) + "-D");
  rotating_ = options.plasticity && options.kinematics == Kinematics::finite_rotation;
  if (!law_ && options.plasticity) {
    if (material.plane == PlaneCondition::stress)
      throw InputError("material.plane: Drucker-Prager plasticity needs plane strain in 2-D");
    auto points = std::make_unique<PlasticPoints>(*options.plasticity, dim_, volume_.size());
    if (options.kinematics == Kinematics::finite_rotation)
      law_ = std::make_unique<FiniteRotationLaw>(std::move(points), dim_);
    else
      law_ = std::move(points);
  }
  if (!law_) law_ = std::make_unique<ElasticPoints>(material, volume_.size());
  C_.resize(static_cast<std::size_t>(dim_) * dim_ * dim_ * dim_);
  material_.tangent(C_.data());  // until the first prepare_tangent
  if (options.follower_pressure) {
    if (!options.plasticity || options.kinematics != Kinematics::finite_rotation)
      throw std::invalid_argument("CorrespondenceModel: follower pressures need finite_rotation kinematics");
    follower_.emplace(dim_);
  }
  if (order_ != 1 && order_ != 2)
    throw std::invalid_argument("CorrespondenceModel: operator_order must be 1 or 2");
  const BondWeights weights = bond_weights(cloud, families, options.influence, options.fitted_rows);
  graph_ = std::make_shared<BondGraph>(families);
  G_ = NonlocalOperator(cloud, graph_, weights,
                        OperatorOptions{order_, false, consistent ? WeightPrecision::float64 : options.weight_precision,
                                        options.fitted_rows});
  const double modulus = modulus_ = options.stabilization * 2.0 * material.mu();  // c_i = modulus / tr K_i
  if (options.stabilization > 0.0 && order_ == 1 && consistent) {
    // S from the uncorrected G (zero on linear fields all the same), stored before G changes
    // and without it: its closed-form rows would read the corrected weights.
    S_ = stored_stabilization(G_, assemble_stabilization(Stabilization(cloud, G_, modulus), particles()),
                              "stabilization S (assembled)");
  } else if (options.stabilization > 0.0) {
    // Order 2 with the consistent formulation: from the uncorrected G too (its scale c_i).
    const StabilizationStorage storage =
        secant_ ? StabilizationStorage::matrix_free : options.stabilization_storage;
    const bool fused = storage == StabilizationStorage::fused ||
                       (storage == StabilizationStorage::automatic && order_ == 1 && G_.graph().symmetric());
    S_ = make_stabilization(cloud, G_, weights, modulus,
                            fused                                        ? AssemblyLevel::fused
                            : storage == StabilizationStorage::matrix_free ? AssemblyLevel::matrix_free
                                                                         : AssemblyLevel::assembled);
  }
  if (consistent) make_consistent(cloud, families, weights, facets, options.weight_precision, options.ranks);
  H_.resize(particles() * dim_ * dim_);
  Q_.resize(particles() * dim_ * dim_);
  if (formulation_ != Formulation::classical && !consistent) P_.resize(particles() * dim_ * dim_);
  if (S_) Su_.resize(particles() * dim_);
}

void CorrespondenceModel::make_consistent(const PointCloud& cloud, const Families& families,
                                          const BondWeights& weights, BoundaryFacets& facets,
                                          WeightPrecision precision, const CorrectionShare* ranks) {
  trace_ = BoundaryTrace(std::move(facets), cloud, G_);
  const std::vector<double> c = trace_.column_measure(particles());
  // The correction keeps G~ exact for linear fields (the patch test); it would keep an order-2 G
  // exact for quadratics too if it used that fit, but the system is then far worse conditioned
  // (the fit's residuals scale with delta^3 instead of delta^2) and stalls near 1e-10 on modest
  // clouds, while the bending results barely move (measured on the 2-D cantilever).
  const NonlocalOperator G1 = order_ == 1 ? NonlocalOperator()
                                           : NonlocalOperator(cloud, G_.shared_graph(), weights,
                                                              OperatorOptions{1, false, WeightPrecision::float64,
                                                                              G_.fitted_rows()});
  ConsistencyOptions copt;
  copt.ranks = ranks;
  std::vector<double> g =
      consistent_gradient_weights(cloud, families, weights, order_ == 1 ? G_ : G1, G_, c, copt, &consistency_);
  if (!consistency_.converged) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "the consistent gradient's correction did not converge (relative "
                  "residual %.3g after %d iterations)", consistency_.residual, consistency_.iterations);
    throw InputError(msg);
  }
  G_ = NonlocalOperator(G_.shared_graph(), dim_, std::move(g), precision);
}

void CorrespondenceModel::gradient(const double* u, double* H) const { G_.apply(u, dim_, H); }

void CorrespondenceModel::limit_rows(std::size_t evaluated, std::size_t written) {
  if (formulation_ != Formulation::classical && formulation_ != Formulation::consistent)
    throw std::logic_error("CorrespondenceModel::limit_rows: the classical and consistent formulations only");
  if (written > evaluated || evaluated > particles())
    throw std::logic_error("CorrespondenceModel::limit_rows: written > evaluated or evaluated > particles");
  G_.limit_rows(evaluated, written);
}

void CorrespondenceModel::internal_force(const double* u, double* f) {
  const int d2 = dim_ * dim_;
  const std::size_t n = G_.gradient_rows();  // particles() unless limit_rows
  if (S_) S_->gradient(u, H_.data());
  else G_.apply(u, dim_, H_.data());
  // S u = G^T(-B) + rest: -B joins V . P in the weak-form product.
  const double* B = S_ ? S_->tensor_part(u, H_.data()) : nullptr;
  const bool strong_rows = formulation_ == Formulation::improved || formulation_ == Formulation::strong;
  for_each_law_block(n, [&](std::size_t lo, std::size_t hi) {
    law_->stresses(lo, hi, H_.data(), Q_.data());
    for (std::size_t i = lo; i < hi; ++i) {
      double* q = Q_.data() + i * d2;
      if (strong_rows) std::copy(q, q + d2, P_.data() + i * d2);
      for (int k = 0; k < d2; ++k) q[k] = q[k] * volume_[i] - (B ? B[i * d2 + k] : 0.0);
    }
  });
  if (!strong_rows) {
    G_.apply_transpose(Q_.data(), dim_, f);
  } else {
    G_.apply_transpose(Q_.data(), dim_, f, &surface_.interior);
    // The band's stabilization G^T(-B), before its rows are overwritten by the strong form.
    if (B) G_.apply_transpose(B, dim_, Su_.data(), &surface_.band);
    G_.divergence(P_.data(), dim_, f, &surface_.band);
    const auto& band = surface_.band;
    const int d = dim_;
#pragma omp parallel for schedule(static)
    for (std::size_t r = 0; r < band.size(); ++r) {
      const std::size_t i = band[r];
      const double* P = P_.data() + i * d2;
      const double* m = surface_.normal_over_h.data() + i * d;
      for (int a = 0; a < d; ++a) {
        double Pm = 0.0;
        for (int b = 0; b < d; ++b) Pm += P[a * d + b] * m[b];
        f[i * d + a] = -volume_[i] * (f[i * d + a] - Pm) - (B ? Su_[i * d + a] : 0.0);
      }
    }
  }
  if (S_) S_->add_rest(u, H_.data(), f);
  if (follower_ && follower_->active()) follower_->add_force(H_.data(), f);
  if (cohesive_) cohesive_->add_force(u, f);
  if (G_.transpose_rows() < particles())
    std::fill(f + G_.transpose_rows() * dim_, f + particles() * dim_, 0.0);
}

void CorrespondenceModel::follow_loads(const Loading& loading, double s) {
  if (follower_) follower_->follow(loading, s);
}

double CorrespondenceModel::energy(const double* u) {
  // The written rows' share (all particles, unless limit_rows): a local part's own energy.
  const std::size_t n = G_.transpose_rows();
  G_.apply(u, dim_, H_.data());
  double* psi = Q_.data();  // the energy densities (Q_ is scratch here)
  for_each_law_block(n, [&](std::size_t lo, std::size_t hi) { law_->energies(lo, hi, H_.data(), psi); });
  // Summed in fixed blocks: the same bits for any thread count.
  double w = parallel_sums<1>(n, [&](std::size_t i, double* acc) { acc[0] += volume_[i] * psi[i]; })[0];
  if (S_) {
    S_->apply(u, H_.data(), Su_.data());  // W_s = 1/2 u . S u
    for (std::size_t k = 0; k < n * dim_; ++k) w += 0.5 * u[k] * Su_[k];
  }
  if (cohesive_) w += cohesive_->energy(u);
  return w;
}

std::vector<double> CorrespondenceModel::lumped_mass() const {
  std::vector<double> m(particles() * dim_);
  for (std::size_t i = 0; i < particles(); ++i)
    for (int a = 0; a < dim_; ++a) m[i * dim_ + a] = material_.density * volume_[i];
  return m;
}

void CorrespondenceModel::visit_rows(
    const PointwiseTangent& C,
    const std::function<void(std::size_t, const std::vector<ParticleId>&,
                             const std::vector<double>&)>& visit,
    const double* local) const {
  const StrongRows strong{surface_.in_band.data(), surface_.normal_over_h.data()};
  const bool strong_rows = formulation_ == Formulation::improved || formulation_ == Formulation::strong;
  for_each_tangent_row(G_, C, S_.get(), visit, strong_rows ? &strong : nullptr, local);
}

void CorrespondenceModel::check_tangent_rows() const {
  if (cohesive_ && cohesive_->size() > 0)
    throw std::logic_error("visit_tangent_rows(rows): the softening bonds' rows are built for the whole model only");
}

void CorrespondenceModel::soften_broken_bonds(const CohesiveLaw& law) {
  if (G_.transpose_rows() < particles()) throw std::logic_error("soften_broken_bonds: not on a limited model");
  cohesive_ = std::make_unique<CohesiveBonds>(dim_, x_, volume_, *graph_, law);
}

void CorrespondenceModel::visit_tangent_rows(const TangentRowVisitor& visit) const {
  // The follower rows as the last prepare_tangent left them; none before the first (the
  // symbolic pattern needs none: they only touch columns G's row already has).
  const std::size_t d3 = static_cast<std::size_t>(dim_) * dim_ * dim_;
  const bool follows = follower_ && follower_->active() && follower_tangent_.size() == particles() * d3;
  const double* local = follows ? follower_tangent_.data() : nullptr;
  const PointwiseTangent C{C_.data(), C_stride_, volume_.data()};
  if (!cohesive_ || cohesive_->size() == 0) return visit_rows(C, visit, local);
  // The softening bonds' rows join G's (their columns may be ones G's row lost with the break).
  visit_rows(C, [&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
    if (!cohesive_->touches(static_cast<ParticleId>(i))) return visit(i, cols, blocks);
    std::vector<ParticleId> merged_cols;
    std::vector<double> merged;
    cohesive_->tangent_row(static_cast<ParticleId>(i), cols, blocks, merged_cols, merged);
    visit(i, merged_cols, merged);
  }, local);
}

void CorrespondenceModel::visit_tangent_rows(const std::vector<ParticleId>& rows, const TangentRowVisitor& visit) const {
  if (formulation_ != Formulation::classical && formulation_ != Formulation::consistent)
    throw std::logic_error("visit_tangent_rows(rows): for the classical and consistent formulations");
  check_tangent_rows();
  if (follower_ && follower_->active()) throw std::logic_error("visit_tangent_rows(rows): not with follower loads");
  for_each_tangent_row(rows, G_, PointwiseTangent{C_.data(), C_stride_, volume_.data()}, S_.get(), visit, true);
}

void CorrespondenceModel::prepare_tangent(const double* u) {
  G_.apply(u, dim_, H_.data());
  if (follower_ && follower_->active()) follower_->tangent(H_.data(), follower_tangent_);
  C_stride_ = law_->tangents(H_.data(), C_);
  if (cohesive_) cohesive_->prepare_tangent(u);
}

const PlasticPoints* CorrespondenceModel::plastic() const {
  if (const auto* wrapper = dynamic_cast<const FiniteRotationLaw*>(law_.get()))
    return dynamic_cast<const PlasticPoints*>(&wrapper->inner());
  return dynamic_cast<const PlasticPoints*>(law_.get());
}

PlasticPoints* CorrespondenceModel::plastic() {
  return const_cast<PlasticPoints*>(static_cast<const CorrespondenceModel&>(*this).plastic());
}

void CorrespondenceModel::commit(const double* u) {
  if (!law_->has_history()) return;
  G_.apply(u, dim_, H_.data());
  for_each_law_block(particles(), [&](std::size_t lo, std::size_t hi) { law_->stresses(lo, hi, H_.data(), Q_.data()); });
  law_->commit();
}

void CorrespondenceModel::begin_step() { follow_secant_stiffness(); }

void CorrespondenceModel::follow_secant_stiffness() {
  if (!secant_) return;
  const PlasticPoints* points = plastic();
  if (!points) throw std::logic_error("CorrespondenceModel: a secant stabilization without a plastic law");
  S_->set_centre_factors(points->secant_ratios());
}

namespace {

// The largest singular value of the d x d block B (row-major): sqrt of B^T B's largest eigenvalue.
template <int D>
double block_norm(const double* b) {
  const Eigen::Map<const Eigen::Matrix<double, D, D, Eigen::RowMajor>> B(b);
  const Eigen::Matrix<double, D, D> M = B.transpose() * B;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>> eig;
  eig.computeDirect(M, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(eig.eigenvalues()[D - 1], 0.0));
}

// sum_j sum_c |K_(i a),(j c)| of a visited block row into sums[slot * d + a]. `rotating`:
// sum_j ||K_ij||_2 into every component instead, the block Gershgorin bound, which a turn of
// the blocks (R K_ij R^T, as finite_rotation's tangent turns with the body) leaves as it is.
// The entries' sums of the unturned blocks fell short of the turned ones': ADR diverged
// turning an elastic block past 19 degrees (1.5 times the mass carried it to 30).
void add_row_sums(int d, std::size_t slot, const std::vector<ParticleId>& cols, const std::vector<double>& blocks,
                  double* sums, bool rotating) {
  for (std::size_t k = 0; k < cols.size(); ++k) {
    if (rotating) {
      const double norm = d == 2 ? block_norm<2>(&blocks[k * 4]) : block_norm<3>(&blocks[k * 9]);
      for (int a = 0; a < d; ++a) sums[slot * d + a] += norm;
      continue;
    }
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c) sums[slot * d + a] += std::abs(blocks[(k * d + a) * d + c]);
  }
}

}  // namespace

std::vector<double> CorrespondenceModel::stiffness_row_sums() const {
  // The elastic stiffness: it bounds the plastic tangents, so the explicit mass stays safe.
  const int d = dim_;
  std::vector<double> sums(particles() * d, 0.0);
  std::vector<double> C(d * d * d * d);
  material_.tangent(C.data());
  visit_rows(PointwiseTangent{C.data(), 0, volume_.data()},
             [&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
               add_row_sums(d, i, cols, blocks, sums.data(), rotating_);
             });
  if (cohesive_) cohesive_->add_row_sums(nullptr, sums.data());
  return sums;
}

std::vector<double> CorrespondenceModel::stiffness_row_sums(const std::vector<ParticleId>& rows) const {
  if (formulation_ != Formulation::classical && formulation_ != Formulation::consistent)
    throw std::logic_error("stiffness_row_sums(rows): for the classical and consistent formulations");
  const int d = dim_;
  if (!std::is_sorted(rows.begin(), rows.end()) || std::adjacent_find(rows.begin(), rows.end()) != rows.end())
    throw std::invalid_argument("stiffness_row_sums(rows): the rows must be sorted and distinct");
  std::vector<double> sums(rows.size() * d, 0.0);
  std::vector<double> C(d * d * d * d);
  material_.tangent(C.data());
  // A stored S0 is read as stored (break_bonds has just refreshed it), not from its closed form.
  for_each_tangent_row(rows, G_, PointwiseTangent{C.data(), 0, volume_.data()}, S_.get(),
                       [&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
                         const auto at = std::lower_bound(rows.begin(), rows.end(), static_cast<ParticleId>(i));
                         add_row_sums(d, static_cast<std::size_t>(at - rows.begin()), cols, blocks, sums.data(),
                                      rotating_);
                       });
  if (cohesive_) cohesive_->add_row_sums(&rows, sums.data());
  return sums;
}

std::vector<std::pair<std::string, std::size_t>> CorrespondenceModel::memory() const {
  std::vector<std::pair<std::string, std::size_t>> m;
  m.emplace_back(order_ == 2 ? "gradient G (second-order fit)" : "gradient operator G and G^T",
                 G_.memory_bytes());
  if (!trace_.empty()) m.emplace_back("boundary facets and their trace", trace_.memory_bytes());
  if (S_) m.emplace_back(S_->name(), S_->memory_bytes());
  m.emplace_back("workspaces (grad u, V.P, P, S u)", (H_.size() + Q_.size() + P_.size() + Su_.size()) * sizeof(double));
  if (cohesive_) m.emplace_back("softening bonds", cohesive_->memory_bytes());
  if (law_->has_history())
    m.emplace_back("material states (committed and trial) and tangents", law_->memory_bytes() + C_.size() * sizeof(double));
  if (formulation_ == Formulation::improved || formulation_ == Formulation::strong)
    m.emplace_back("surface normals and band E",
                   surface_.normal_over_h.size() * sizeof(double) +
                       2 * surface_.in_band.size() * sizeof(std::uint8_t) +
                       (surface_.band.size() + surface_.interior.size()) * sizeof(ParticleId));
  return m;
}

void CorrespondenceModel::stress3(const double* u, std::vector<double>& sigma) const {
  const int d2 = dim_ * dim_;
  std::vector<double> H(particles() * d2);
  gradient(u, H.data());
  sigma.resize(particles() * 9);
  law_->cauchy(H.data(), sigma.data());
}

}  // namespace perinom

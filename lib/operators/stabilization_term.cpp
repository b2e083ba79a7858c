#include "perinom/operators/stabilization_term.hpp"

#include <optional>
#include <stdexcept>

#include "perinom/core/error.hpp"
#include "perinom/core/parallel.hpp"
#include "perinom/operators/fused_stabilization.hpp"
#include "perinom/operators/stabilization.hpp"

namespace perinom {
namespace {

// S u = G^T(-B) + the direct bond pass (Stabilization).
class MatrixFreeTerm final : public StabilizationTerm {
 public:
  MatrixFreeTerm(const PointCloud& cloud, const NonlocalOperator& G, double modulus)
      : StabilizationTerm(G), S_(cloud, G, modulus), B_(cloud.size() * cloud.dim * cloud.dim),
        r_(cloud.size() * cloud.dim) {}
  AssemblyLevel level() const override { return AssemblyLevel::matrix_free; }
  const double* tensor_part(const double* u, const double* H) override {
    S_.bond_terms(u, H, B_.data(), r_.data());
    return B_.data();
  }
  void add_rest(const double* u, const double* H, double* f) override { S_.add_direct(u, H, r_.data(), f); }
  void add_row(std::size_t i, RowAccumulator& acc, int copies) const override { S_.add_row(i, acc, copies); }
  void refresh_rows(const std::vector<ParticleId>& rows) override { S_.refresh_rows(rows); }
  void set_centre_factors(std::vector<double> factor) override { S_.set_centre_factors(std::move(factor)); }
  std::string name() const override { return "stabilization (matrix-free)"; }
  std::size_t memory_bytes() const override {
    return S_.memory_bytes() + (B_.size() + r_.size()) * sizeof(double);
  }

 private:
  Stabilization S_;
  std::vector<double> B_, r_;
};

// S u = -lap(u) - G^T(T): lap from the gradient pass, T = cv_i H_i K_i (FusedStabilization);
// the rows of S0 from the closed form (Stabilization).
class FusedTerm final : public StabilizationTerm {
 public:
  FusedTerm(const PointCloud& cloud, const NonlocalOperator& G, double modulus, FusedStabilization F)
      : StabilizationTerm(G), S_(cloud, G, modulus), F_(std::move(F)), T_(cloud.size() * cloud.dim * cloud.dim),
        lap_(cloud.size() * cloud.dim) {}
  AssemblyLevel level() const override { return AssemblyLevel::fused; }
  void gradient(const double* u, double* H) override { F_.gradient_and_laplacian(u, H, lap_.data()); }
  const double* tensor_part(const double*, const double* H) override {
    F_.tensor_terms(H, T_.data());
    return T_.data();
  }
  void add_rest(const double*, const double*, double* f) override {
    const double* lap = lap_.data();
    parallel_for(lap_.size(), [f, lap](std::size_t k) { f[k] -= lap[k]; });
  }
  void add_row(std::size_t i, RowAccumulator& acc, int copies) const override { S_.add_row(i, acc, copies); }
  void refresh_rows(const std::vector<ParticleId>& rows) override {
    S_.refresh_rows(rows);
    F_.refresh_rows(rows);
  }
  std::string name() const override { return "stabilization (fused)"; }
  std::size_t memory_bytes() const override {
    return S_.memory_bytes() + F_.memory_bytes() + (T_.size() + lap_.size()) * sizeof(double);
  }

 private:
  Stabilization S_;
  FusedStabilization F_;
  std::vector<double> T_, lap_;
};

// S0 stored; with the operator it came from (S_) its rows refresh, and the tangent rows take
// the closed form from S_ as the other levels do (the same bits whatever the level).
class AssembledTerm final : public StabilizationTerm {
 public:
  AssembledTerm(const NonlocalOperator& G, ScalarCsr S0, std::string name, std::optional<Stabilization> source)
      : StabilizationTerm(G), S_(std::move(source)), S0_(std::move(S0)), name_(std::move(name)) {}
  AssemblyLevel level() const override { return AssemblyLevel::assembled; }
  const double* tensor_part(const double*, const double*) override { return nullptr; }
  void add_rest(const double* u, const double*, double* f) override { S0_.apply_add(u, G_->dim(), f); }
  void add_row(std::size_t i, RowAccumulator& acc, int copies) const override {
    if (S_) return S_->add_row(i, acc, copies);
    add_stored_row(S0_, i, acc, copies);
  }
  void refresh_rows(const std::vector<ParticleId>& rows) override {
    require_source();
    S_->refresh_rows(rows);
    refresh_stabilization(S0_, *S_, G_->graph(), rows);
  }
  void refresh_rows(const std::vector<ParticleId>& rows, const std::function<void()>& change) override {
    require_source();
    S_->add_blocks(S0_, rows, -1.0);
    change();
    S_->refresh_rows(rows);
    S_->add_blocks(S0_, rows, 1.0);
  }
  std::string name() const override { return name_; }
  std::size_t memory_bytes() const override { return S0_.memory_bytes() + (S_ ? S_->memory_bytes() : 0); }
  const ScalarCsr* stored() const override { return &S0_; }
  bool refreshable() const override { return S_.has_value(); }

 private:
  void require_source() const {
    if (!S_)
      throw std::logic_error("StabilizationTerm: " + name_ + " was stored without the operator it came from; "
                             "a refresh needs a rebuild");
  }
  std::optional<Stabilization> S_;
  ScalarCsr S0_;
  std::string name_;
};

// The second-order operator energy (seed 002 eq. 35-39) of the d components, matrix-free: the
// fit with its Hessian kept, one bond pass in each order. Refreshable.
class SecondOrderMatrixFreeTerm final : public StabilizationTerm {
 public:
  SecondOrderMatrixFreeTerm(const PointCloud& cloud, const NonlocalOperator& G, const BondWeights& weights,
                            double modulus)
      : StabilizationTerm(G), fit_(cloud, G.shared_graph(), weights, OperatorOptions{2, true, WeightPrecision::float64, G.fitted_rows()}),
        S_(cloud, fit_, shape_scale(G, modulus, cloud.volume)), grad_(cloud.size() * cloud.dim * cloud.dim),
        hess_(cloud.size() * cloud.dim * fit_.hessian_terms()) {}
  AssemblyLevel level() const override { return AssemblyLevel::matrix_free; }
  const double* tensor_part(const double*, const double*) override { return nullptr; }
  void add_rest(const double* u, const double*, double* f) override {
    const int d = G_->dim();
    fit_.apply(u, d, grad_.data());
    fit_.apply(u, d, hess_.data(), Derivative::hessian);
    S_.add_force(u, d, grad_.data(), hess_.data(), f);
  }
  void add_row(std::size_t i, RowAccumulator& acc, int copies) const override { S_.add_row(i, acc, copies); }
  void refresh_rows(const std::vector<ParticleId>& rows) override {
    fit_.refresh_rows(rows);
    S_.refresh_rows(rows);
  }
  void set_centre_factors(std::vector<double> factor) override { S_.set_centre_factors(std::move(factor)); }
  std::string name() const override { return "second-order stabilization (matrix-free)"; }
  std::size_t memory_bytes() const override {
    return fit_.memory_bytes() + S_.memory_bytes() + (grad_.size() + hess_.size()) * sizeof(double);
  }

 private:
  NonlocalOperator fit_;
  Stabilization S_;
  std::vector<double> grad_, hess_;  // the fit's derivatives of u
};

}  // namespace

void add_stored_row(const ScalarCsr& S0, std::size_t i, RowAccumulator& acc, int copies) {
  for (Offset k = S0.offsets[i]; k < S0.offsets[i + 1]; ++k) {
    double* block = acc.at(S0.cols[k]);
    for (int a = 0; a < copies; ++a) block[a * (copies + 1)] += S0.values[k];
  }
}

void StabilizationTerm::gradient(const double* u, double* H) { G_->apply(u, G_->dim(), H); }

void StabilizationTerm::set_centre_factors(std::vector<double>) {
  throw std::logic_error("StabilizationTerm: " + name() + " cannot scale its centres (the matrix-free levels can)");
}

void StabilizationTerm::refresh_rows(const std::vector<ParticleId>& rows, const std::function<void()>& change) {
  change();
  refresh_rows(rows);
}

void StabilizationTerm::apply(const double* u, double* H, double* Su) {
  const int d = G_->dim();
  const std::size_t n = G_->rows() * static_cast<std::size_t>(d);
  gradient(u, H);
  if (const double* B = tensor_part(u, H)) {
    G_->apply_transpose(B, d, Su);
    for (std::size_t k = 0; k < n; ++k) Su[k] = -Su[k];
  } else {
    std::fill(Su, Su + n, 0.0);
  }
  add_rest(u, H, Su);
}

std::unique_ptr<StabilizationTerm> make_stabilization(const PointCloud& cloud, const NonlocalOperator& G,
                                                      double modulus, AssemblyLevel level) {
  switch (level) {
    case AssemblyLevel::fused: {
      std::optional<FusedStabilization> F = FusedStabilization::make(cloud, G, modulus);
      if (!F)
        throw InputError("model.stabilization_storage: fused needs symmetric families (a horizon "
                         "radius, not a neighbour count); use assembled or matrix_free");
      return std::make_unique<FusedTerm>(cloud, G, modulus, std::move(*F));
    }
    case AssemblyLevel::matrix_free:
      return std::make_unique<MatrixFreeTerm>(cloud, G, modulus);
    case AssemblyLevel::assembled: {
      Stabilization S(cloud, G, modulus);
      ScalarCsr S0 = assemble_stabilization(S, cloud.size());
      return std::make_unique<AssembledTerm>(G, std::move(S0), "stabilization S (assembled)", std::move(S));
    }
  }
  throw std::logic_error("make_stabilization: unknown assembly level");
}

std::unique_ptr<StabilizationTerm> make_stabilization(const PointCloud& cloud, const NonlocalOperator& G,
                                                      const BondWeights& weights, double modulus, AssemblyLevel level) {
  if (G.order() == 1) return make_stabilization(cloud, G, modulus, level);
  switch (level) {
    case AssemblyLevel::fused:
      throw InputError("model.stabilization_storage: fused rests on the first-order fit's identities; with "
                       "model.operator_order 2 use auto, assembled or matrix_free");
    case AssemblyLevel::matrix_free:
      return std::make_unique<SecondOrderMatrixFreeTerm>(cloud, G, weights, modulus);
    case AssemblyLevel::assembled: {
      // The Hessian weights only enter z_ij (seed 002 eq. 35): S is stored, the fit dropped.
      const NonlocalOperator fit(cloud, G.shared_graph(), weights, OperatorOptions{2, true, WeightPrecision::float64, G.fitted_rows()});
      const Stabilization S(cloud, fit, shape_scale(G, modulus, cloud.volume));
      return stored_stabilization(G, assemble_stabilization(S, cloud.size()), "second-order stabilization S");
    }
  }
  throw std::logic_error("make_stabilization: unknown assembly level");
}

std::unique_ptr<StabilizationTerm> stored_stabilization(const NonlocalOperator& G, ScalarCsr S, std::string name) {
  return std::make_unique<AssembledTerm>(G, std::move(S), std::move(name), std::nullopt);
}

}  // namespace perinom

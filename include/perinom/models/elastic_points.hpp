#pragma once
/// @file Linear elasticity at every particle: the pointwise law without history.
#include "perinom/materials/linear_elastic.hpp"
#include "perinom/models/pointwise_law.hpp"

namespace perinom {

/// P_i = LinearElastic::stress(H_i) at each of N particles; one tangent serves them all.
class ElasticPoints final : public PointwiseLaw {
 public:
  ElasticPoints(const LinearElastic& material, std::size_t particles)
      : material_(material), particles_(particles) {}
  const LinearElastic& material() const { return material_; }

  int dim() const override { return material_.dim; }
  std::size_t size() const override { return particles_; }
  bool has_history() const override { return false; }
  void stresses(std::size_t begin, std::size_t end, const double* H, double* P) override;
  void energies(std::size_t begin, std::size_t end, const double* H, double* psi) override;
  std::size_t tangents(const double* H, std::vector<double>& C) const override;
  void cauchy(const double* H, double* sigma) const override;
  void commit() override {}
  std::size_t memory_bytes() const override { return 0; }
  std::vector<LawField> fields() const override { return {{"stress", 9}}; }
  void field(const std::string& name, const double* H, std::vector<double>& values) const override;

 private:
  LinearElastic material_;
  std::size_t particles_;
};

}  // namespace perinom

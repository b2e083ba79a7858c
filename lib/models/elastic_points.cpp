#include "perinom/models/elastic_points.hpp"

#include <stdexcept>

#include "perinom/core/parallel.hpp"

namespace perinom {

void ElasticPoints::stresses(std::size_t begin, std::size_t end, const double* H, double* P) {
  const std::size_t d2 = static_cast<std::size_t>(material_.dim) * material_.dim;
  for (std::size_t i = begin; i < end; ++i) material_.stress(H + i * d2, P + i * d2);
}

void ElasticPoints::energies(std::size_t begin, std::size_t end, const double* H, double* psi) {
  const std::size_t d2 = static_cast<std::size_t>(material_.dim) * material_.dim;
  for (std::size_t i = begin; i < end; ++i) psi[i] = material_.energy(H + i * d2);
}

std::size_t ElasticPoints::tangents(const double*, std::vector<double>& C) const {
  const int d = material_.dim;
  C.resize(static_cast<std::size_t>(d) * d * d * d);
  material_.tangent(C.data());
  return 0;
}

void ElasticPoints::cauchy(const double* H, double* sigma) const {
  const std::size_t d2 = static_cast<std::size_t>(material_.dim) * material_.dim;
  parallel_for(particles_, [&](std::size_t i) { material_.stress3(H + i * d2, sigma + i * 9); });
}

void ElasticPoints::field(const std::string& name, const double* H, std::vector<double>& values) const {
  if (name != "stress") throw std::invalid_argument("ElasticPoints: no output field '" + name + "' (it offers: stress)");
  values.resize(particles_ * 9);
  cauchy(H, values.data());
}

}  // namespace perinom

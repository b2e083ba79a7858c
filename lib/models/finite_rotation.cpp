#include "perinom/models/finite_rotation.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "polar.hpp"

namespace perinom {

using detail::Mat3;
using detail::rotation;

namespace {

constexpr double kIdentity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

/// The d x d block of a 3 x 3 tensor.
void in_plane(const Mat3& t3, int d, double* t) {
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) t[a * d + b] = t3(a, b);
}

/// R sigma_u R^T with R the rotation of F.
Mat3 rotated(const Mat3& F, const double* sigma_u) {
  const Mat3 R = rotation(F);
  return R * Eigen::Map<const Mat3>(sigma_u) * R.transpose();
}

}  // namespace

FiniteRotationLaw::FiniteRotationLaw(std::unique_ptr<IncrementalLaw> law, int dim) : law_(std::move(law)), dim_(dim) {
  if (!law_) throw std::invalid_argument("FiniteRotationLaw: no law to wrap");
  if (dim_ != 2 && dim_ != 3) throw std::invalid_argument("FiniteRotationLaw: dim must be 2 or 3");
  if (!law_->history()) throw std::invalid_argument("FiniteRotationLaw: the wrapped law keeps no history");
  committed_F_.resize(size() * 9);
  for (std::size_t i = 0; i < size(); ++i) std::copy(kIdentity, kIdentity + 9, committed_F_.begin() + i * 9);
  trial_F_ = committed_F_;
}

LawHistory& FiniteRotationLaw::inner_history() const { return *law_->history(); }

void FiniteRotationLaw::increment(std::size_t i, const double* H, double* F_out, double* deps) const {
  const int d = dim_;
  Mat3 F = Mat3::Identity();
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) F(a, b) += H[a * d + b];
  const Mat3 Fn = Eigen::Map<const Mat3>(committed_F_.data() + i * 9);
  const Mat3 Fm = 0.5 * (F + Fn);
  const Mat3 L = (F - Fn) * Fm.inverse();
  const Mat3 Rm = rotation(Fm);
  const Mat3 D = Rm.transpose() * (0.5 * (L + L.transpose())) * Rm;
  Eigen::Map<Mat3>{F_out} = F;
  Eigen::Map<Mat3>{deps} = D;
}

void FiniteRotationLaw::stress(std::size_t i, const double* H, double* P) {
  double* F_data = trial_F_.data() + i * 9;
  double deps[9], sigma_u[9];
  increment(i, H, F_data, deps);
  law_->update(i, deps, sigma_u);
  const Mat3 F = Eigen::Map<const Mat3>(F_data);
  const Mat3 sigma = rotated(F, sigma_u);
  const Mat3 P3 = F.determinant() * sigma * F.inverse().transpose();
  in_plane(P3, dim_, P);
}

void FiniteRotationLaw::cauchy(std::size_t i, const double* H, double* sigma) const {
  double F[9], deps[9], sigma_u[9];
  increment(i, H, F, deps);
  law_->evaluate(i, deps, sigma_u);
  Eigen::Map<Mat3>{sigma} = rotated(Eigen::Map<const Mat3>(F), sigma_u);
}

void FiniteRotationLaw::commit() {
  law_->commit();
  committed_F_ = trial_F_;
}

std::vector<LawField> FiniteRotationLaw::fields() const {
  std::vector<LawField> out{{"stress", 9}};
  for (auto& f : law_->state_fields()) out.push_back(std::move(f));
  return out;
}

void FiniteRotationLaw::field(const std::string& name, const double* H, std::vector<double>& values) const {
  if (name != "stress") return law_->state_field(name, values);
  values.resize(size() * 9);
  cauchy(H, values.data());
}

std::size_t FiniteRotationLaw::memory_bytes() const {
  return law_->memory_bytes() + (committed_F_.size() + trial_F_.size()) * sizeof(double);
}

std::vector<double> FiniteRotationLaw::history_variable() const { return inner_history().history_variable(); }

std::size_t FiniteRotationLaw::values_per_particle() const { return inner_history().values_per_particle() + 9; }

HistoryState FiniteRotationLaw::save_history() const {
  HistoryState inner = inner_history().save_history();
  const std::size_t m = inner_history().values_per_particle();
  HistoryState s;
  s.values.reserve(size() * (m + 9));
  for (std::size_t i = 0; i < size(); ++i) {
    s.values.insert(s.values.end(), inner.values.begin() + i * m, inner.values.begin() + (i + 1) * m);
    s.values.insert(s.values.end(), committed_F_.begin() + i * 9, committed_F_.begin() + (i + 1) * 9);
  }
  s.flags = std::move(inner.flags);
  return s;
}

void FiniteRotationLaw::restore_history(const HistoryState& s) {
  const std::size_t m = inner_history().values_per_particle(), n = s.flags.size();
  if (s.values.size() != n * (m + 9) || n != size())
    throw std::invalid_argument("FiniteRotationLaw: the history holds " + std::to_string(s.values.size()) +
                                " values and " + std::to_string(n) + " flags for " + std::to_string(size()) +
                                " particles (" + std::to_string(m + 9) + " values per particle)");
  HistoryState inner;
  inner.values.reserve(n * m);
  std::vector<double> F(n * 9);
  for (std::size_t i = 0; i < n; ++i) {
    const auto at = s.values.begin() + i * (m + 9);
    inner.values.insert(inner.values.end(), at, at + m);
    std::copy(at + m, at + m + 9, F.begin() + i * 9);
  }
  inner.flags = s.flags;
  inner_history().restore_history(inner);
  committed_F_ = std::move(F);
  trial_F_ = committed_F_;
}

void FiniteRotationLaw::reset_history() {
  inner_history().reset_history();
  for (std::size_t i = 0; i < size(); ++i) std::copy(kIdentity, kIdentity + 9, committed_F_.begin() + i * 9);
  trial_F_ = committed_F_;
}

}  // namespace perinom

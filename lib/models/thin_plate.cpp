#include "perinom/models/thin_plate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "perinom/core/error.hpp"
#include "perinom/operators/bond_weights.hpp"
#include "perinom/operators/row_accumulator.hpp"

namespace perinom {
namespace {

/// The options a plate is built from, as the scene reader checks its keys: a library caller's
/// thickness of 0 made D0 = 0 and a singular stiffness named nowhere.
const ThinPlateOptions& checked(const ThinPlateOptions& o) {
  auto refuse = [](const char* field, double v, const char* rule) {
    char text[160];
    std::snprintf(text, sizeof text, "ThinPlateOptions::%s = %g: %s", field, v, rule);
    throw InputError(text);
  };
  if (!(o.E > 0.0 && std::isfinite(o.E))) refuse("E", o.E, "must be positive and finite");
  if (!(o.nu > -1.0 && o.nu < 0.5)) refuse("nu", o.nu, "must lie in (-1, 0.5)");
  if (!(o.thickness > 0.0 && std::isfinite(o.thickness))) refuse("thickness", o.thickness, "must be positive and finite");
  if (!(o.density > 0.0 && std::isfinite(o.density))) refuse("density", o.density, "must be positive and finite");
  if (!(o.stabilization >= 0.0 && std::isfinite(o.stabilization)))
    refuse("stabilization", o.stabilization, "must be zero or positive, and finite");
  return o;
}

}  // namespace

ThinPlateModel::ThinPlateModel(PlateCloud plate, const Families& families, const ThinPlateOptions& opt)
    : plate_(std::move(plate)), opt_(checked(opt)),
      D0_(opt.E * std::pow(opt.thickness, 3) / (12.0 * (1.0 - opt.nu * opt.nu))) {
  const PointCloud& c = plate_.cloud;
  const std::size_t n = c.size(), phys = plate_.physical;
  const BondWeights bw = bond_weights(c, families, opt.influence, opt.fitted_rows);
  OperatorOptions o{2, true};
  o.fitted_rows = opt.fitted_rows;
  op_ = NonlocalOperator(c, families, bw, o);
  if (opt.stabilization > 0.0) {
    std::vector<double> area(n, 0.0);  // the ghosts and the unfitted nodes carry none
    std::copy(plate_.area.begin(), plate_.area.begin() + std::ptrdiff_t(std::min(phys, opt.fitted_rows)), area.begin());
    S_.emplace(c, op_, bending_scale(op_, opt.stabilization, D0_, std::move(area)));
  }
  ghost_off_.assign(phys + 1, 0);
  for (const ParticleId m : plate_.image) ++ghost_off_[m + 1];
  for (std::size_t m = 0; m < phys; ++m) ghost_off_[m + 1] += ghost_off_[m];
  ghost_list_.resize(plate_.image.size());
  std::vector<Offset> next(ghost_off_.begin(), ghost_off_.end() - 1);
  for (std::size_t g = 0; g < plate_.image.size(); ++g)
    ghost_list_[next[plate_.image[g]]++] = static_cast<ParticleId>(phys + g);
  ext_.assign(n, 0.0);
  grad_.assign(n * 2, 0.0);
  hess_.assign(n * 3, 0.0);
  Q_.assign(n * 3, 0.0);
  fe_.assign(n, 0.0);
}

void ThinPlateModel::extend(const double* w, std::vector<double>& ext) const {
  const std::size_t phys = plate_.physical;
  std::copy(w, w + phys, ext.begin());
  for (std::size_t g = 0; g < plate_.image.size(); ++g) ext[phys + g] = plate_.sign[g] * w[plate_.image[g]];
}

void ThinPlateModel::derivatives(const double* w) {
  extend(w, ext_);
  op_.apply(ext_.data(), 1, grad_.data());
  op_.apply(ext_.data(), 1, hess_.data(), Derivative::hessian);
}

void ThinPlateModel::moment(const double* k, double* M) const {
  M[0] = D0_ * (k[0] + opt_.nu * k[2]);
  M[1] = D0_ * (1.0 - opt_.nu) * k[1];
  M[2] = D0_ * (k[2] + opt_.nu * k[0]);
}

void ThinPlateModel::internal_force(const double* w, double* f) {
  derivatives(w);
  const std::size_t phys = plate_.physical;
  for (std::size_t i = 0; i < std::min(phys, evaluated_); ++i) {  // the others' Q stays zero
    double M[3];
    moment(hess_.data() + i * 3, M);
    const double A = plate_.area[i];
    Q_[i * 3] = A * M[0], Q_[i * 3 + 1] = 2.0 * A * M[1], Q_[i * 3 + 2] = A * M[2];
  }
  op_.apply_transpose(Q_.data(), 1, fe_.data(), nullptr, Derivative::hessian);
  if (S_) S_->add_force(ext_.data(), 1, grad_.data(), hess_.data(), fe_.data());
  std::copy(fe_.begin(), fe_.begin() + phys, f);
  for (std::size_t g = 0; g < plate_.image.size(); ++g) f[plate_.image[g]] += plate_.sign[g] * fe_[phys + g];
}

double ThinPlateModel::energy(const double* w) {
  if (written_ < plate_.physical) {  // a rank's share: W = 1/2 w . f(w), W being quadratic
    internal_force(w, share_.data());
    double W = 0.0;
    for (std::size_t r = 0; r < written_; ++r) W += 0.5 * w[r] * share_[r];
    return W;
  }
  derivatives(w);
  double W = 0.0;
  for (std::size_t i = 0; i < plate_.physical; ++i) {
    const double* k = hess_.data() + i * 3;
    double M[3];
    moment(k, M);
    W += 0.5 * plate_.area[i] * (M[0] * k[0] + 2.0 * M[1] * k[1] + M[2] * k[2]);
  }
  return W + (S_ ? S_->energy(ext_.data(), 1, grad_.data(), hess_.data()) : 0.0);
}

std::vector<double> ThinPlateModel::lumped_mass() const {
  std::vector<double> m(plate_.physical);
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = opt_.density * opt_.thickness * plate_.area[i];
  return m;
}

RowFill ThinPlateModel::row_fill() const {
  // The row of r and those of its ghosts, folded: a ghost's row adds with its sign.
  return [this](std::size_t r, RowAccumulator& acc) {
    const std::size_t phys = plate_.physical;
    const NonlocalOperator& H = op_;
    constexpr Derivative hessian = Derivative::hessian;
    double sa = 1.0;  // the sign of the row being added
    const std::function<void(ParticleId, double)> add = [&](ParticleId b, double v) {
      double sb = 1.0;
      ParticleId m = b;
      if (static_cast<std::size_t>(b) >= phys) sb = plate_.sign[b - phys], m = plate_.image[b - phys];
      *acc.at(m) += sa * sb * v;
    };
    for (Offset q = -1; q < ghost_off_[r + 1] - ghost_off_[r]; ++q) {
      const std::size_t a = q < 0 ? r : static_cast<std::size_t>(ghost_list_[ghost_off_[r] + q]);
      sa = q < 0 ? 1.0 : plate_.sign[a - phys];
      // Bending: K_ab = sum_i A_i h_ia . Dm h_ib over the centres i that see a.
      // (visit_column gives the centre a itself first, with its diagonal.)
      H.visit_column(a, [&](ParticleId i, const double* h_ia) {
        if (static_cast<std::size_t>(i) >= std::min(phys, evaluated_)) return;
        double v[3];
        moment(h_ia, v);
        v[1] *= 2.0;
        for (double& x : v) x *= plate_.area[i];
        H.visit_row(i, [&](ParticleId j, const double* h_ij) { add(j, v[0] * h_ij[0] + v[1] * h_ij[1] + v[2] * h_ij[2]); },
                    hessian);
      }, hessian);
      if (S_) S_->add_row(a, add);
    }
  };
}

void ThinPlateModel::visit_tangent_rows(const TangentRowVisitor& visit) const {
  for_each_block_row(plate_.physical, plate_.physical, 1, [this] { return row_fill(); }, visit);
}

void ThinPlateModel::visit_tangent_rows(const std::vector<ParticleId>& rows, const TangentRowVisitor& visit) const {
  for_each_block_row(rows, plate_.physical, 1, [this] { return row_fill(); }, visit);
}

std::vector<double> ThinPlateModel::stiffness_row_sums() const {
  std::vector<double> sums(plate_.physical, 0.0);
  visit_tangent_rows([&](std::size_t r, const std::vector<ParticleId>&, const std::vector<double>& v) {
    for (const double x : v) sums[r] += std::abs(x);
  });
  return sums;
}

std::vector<double> ThinPlateModel::stiffness_row_sums(const std::vector<ParticleId>& rows) const {
  std::vector<double> sums(rows.size(), 0.0);
  visit_tangent_rows(rows, [&](std::size_t r, const std::vector<ParticleId>&, const std::vector<double>& v) {
    const auto at = std::lower_bound(rows.begin(), rows.end(), static_cast<ParticleId>(r)) - rows.begin();
    for (const double x : v) sums[static_cast<std::size_t>(at)] += std::abs(x);
  });
  return sums;
}

void ThinPlateModel::limit_rows(std::size_t evaluated, std::size_t written) {
  if (written > evaluated || evaluated > std::min(plate_.physical, op_.fitted_rows()))
    throw std::logic_error("ThinPlateModel::limit_rows: written > evaluated or evaluated beyond the fitted nodes");
  evaluated_ = evaluated, written_ = written;
  share_.assign(written < plate_.physical ? plate_.physical : 0, 0.0);
  op_.limit_rows(evaluated, SIZE_MAX);  // every row's transpose: the mirrors' forces fold onto their images
}

void ThinPlateModel::curvature(const double* w, double* kappa) const {
  std::vector<double> ext(plate_.cloud.size()), hess(plate_.cloud.size() * 3);
  extend(w, ext);
  op_.apply(ext.data(), 1, hess.data(), Derivative::hessian);
  std::copy(hess.begin(), hess.begin() + plate_.physical * 3, kappa);
}

void ThinPlateModel::moments(const double* w, double* M) const {
  curvature(w, M);
  for (std::size_t i = 0; i < plate_.physical; ++i) {
    const double k[3] = {M[i * 3], M[i * 3 + 1], M[i * 3 + 2]};
    moment(k, M + i * 3);
  }
}

std::vector<std::pair<std::string, std::size_t>> ThinPlateModel::memory() const {
  std::vector<std::pair<std::string, std::size_t>> m;
  m.emplace_back("second-order operator (g, h)", op_.memory_bytes());
  if (S_) m.emplace_back("plate stabilization", S_->memory_bytes());
  m.emplace_back("workspaces (w, grad, kappa, M)",
                 (ext_.size() + grad_.size() + hess_.size() + Q_.size() + fe_.size()) * sizeof(double) +
                     ghost_off_.size() * sizeof(Offset));
  return m;
}

}  // namespace perinom

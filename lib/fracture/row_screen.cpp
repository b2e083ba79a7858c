#include "row_screen.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace perinom::detail {

RowScreen::RowScreen(const PointCloud& cloud, const BondGraph& graph) : d_(cloud.dim), particles_(cloud.size()) {
  if (d_ < 1 || d_ > 3) throw std::invalid_argument("RowScreen: dimension must be 1, 2 or 3");
  if (graph.rows() != particles_ || graph.columns() != particles_)
    throw std::invalid_argument("RowScreen: the graph's rows and columns must be the cloud's particles");
  const double* x = cloud.x.data();
  std::vector<double> shortest(particles_, std::numeric_limits<double>::infinity());
  double longest = 0.0;
  for (std::size_t i = 0; i < particles_; ++i)
    for (Offset k = graph.begin(i); k < graph.end(i); ++k) {
      const std::size_t j = graph.col(k);
      double l2 = 0.0;
      for (int a = 0; a < d_; ++a) l2 += (x[j * d_ + a] - x[i * d_ + a]) * (x[j * d_ + a] - x[i * d_ + a]);
      shortest[i] = std::min(shortest[i], std::sqrt(l2));
      longest = std::max(longest, std::sqrt(l2));
    }
  // 1 / the shortest bond: 0 for a row without bonds, infinite for coincident particles (a
  // row the screen always keeps).
  inverse_shortest_.resize(particles_);
  for (std::size_t i = 0; i < particles_; ++i) inverse_shortest_[i] = 1.0 / shortest[i];
  // Cells at least as wide as the longest bond on each axis: a family lies in the 3^d cells
  // around its centre's.
  double lo[3] = {0, 0, 0}, width[3] = {1, 1, 1};
  for (int a = 0; a < d_; ++a) {
    double top = -std::numeric_limits<double>::infinity();
    lo[a] = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < particles_; ++i) lo[a] = std::min(lo[a], x[i * d_ + a]), top = std::max(top, x[i * d_ + a]);
    const double extent = particles_ ? top - lo[a] : 0.0;
    cells_[a] = longest > 0.0 ? std::max(1, static_cast<int>(std::min(extent / longest, 1e6))) : 1;
    width[a] = extent > 0.0 ? extent / cells_[a] : 1.0;
  }
  cell_of_.resize(particles_);
  std::size_t cells = 1;
  for (int a = 0; a < d_; ++a) cells *= static_cast<std::size_t>(cells_[a]);
  cell_begin_.assign(cells + 1, 0);
  for (std::size_t i = 0; i < particles_; ++i) {
    int c[3] = {0, 0, 0};
    for (int a = 0; a < d_; ++a)
      c[a] = std::min(cells_[a] - 1, std::max(0, static_cast<int>((x[i * d_ + a] - lo[a]) / width[a])));
    cell_of_[i] = cell_index(c);
    ++cell_begin_[cell_of_[i] + 1];
  }
  for (std::size_t c = 1; c < cell_begin_.size(); ++c) cell_begin_[c] += cell_begin_[c - 1];
  cell_members_.resize(particles_);
  std::vector<std::size_t> fill(cell_begin_.begin(), cell_begin_.end() - 1);
  for (std::size_t i = 0; i < particles_; ++i) cell_members_[fill[cell_of_[i]]++] = static_cast<ParticleId>(i);
}

std::size_t RowScreen::cell_index(const int* c) const {
  std::size_t index = 0;  // row-major
  for (int a = 0; a < d_; ++a) index = index * static_cast<std::size_t>(cells_[a]) + static_cast<std::size_t>(c[a]);
  return index;
}

void RowScreen::take(const double* u, const double* H, std::vector<double> row_max) {
  if (row_max.size() != particles_) throw std::invalid_argument("RowScreen::take: one maximum per row");
  u0_.assign(u, u + particles_ * d_);
  if (H) H0_.assign(H, H + particles_ * d_ * d_);
  else H0_.clear();
  r_ = std::move(row_max);
}

void RowScreen::cell_boxes(const double* u) {
  // Inside the caller's parallel region: the boxes of du by cell, then over each cell's 3^d
  // neighbours.
  const int d = d_;
  const std::size_t cells = cell_begin_.size() - 1;
  constexpr double inf = std::numeric_limits<double>::infinity();
#pragma omp for schedule(static)
  for (std::size_t c = 0; c < cells; ++c) {
    const double* u0 = u0_.data();
    double lo[3] = {inf, inf, inf}, hi[3] = {-inf, -inf, -inf};  // in registers, not in box_
    for (std::size_t m = cell_begin_[c]; m < cell_begin_[c + 1]; ++m) {
      const std::size_t k = cell_members_[m];
      for (int a = 0; a < d; ++a) {
        const double du = u[k * d + a] - u0[k * d + a];
        lo[a] = std::min(lo[a], du), hi[a] = std::max(hi[a], du);
      }
    }
    double* b = box_.data() + c * 2 * d;
    for (int a = 0; a < d; ++a) b[a] = lo[a], b[d + a] = hi[a];
  }
#pragma omp for schedule(static)
  for (std::size_t c = 0; c < cells; ++c) {
    int at[3] = {0, 0, 0};
    for (std::size_t rest = c, a = d; a-- > 0;) at[a] = static_cast<int>(rest % cells_[a]), rest /= cells_[a];
    double* n = near_.data() + c * 2 * d;
    for (int a = 0; a < d; ++a) n[a] = inf, n[d + a] = -inf;
    int o[3] = {0, 0, 0};
    for (o[0] = -1; o[0] <= 1; ++o[0])
      for (o[1] = (d > 1 ? -1 : 0); o[1] <= (d > 1 ? 1 : 0); ++o[1])
        for (o[2] = (d > 2 ? -1 : 0); o[2] <= (d > 2 ? 1 : 0); ++o[2]) {
          int q[3];
          bool inside = true;
          for (int a = 0; a < d; ++a) q[a] = at[a] + o[a], inside = inside && q[a] >= 0 && q[a] < cells_[a];
          if (!inside) continue;
          const double* b = box_.data() + cell_index(q) * 2 * d;
          for (int a = 0; a < d; ++a) n[a] = std::min(n[a], b[a]), n[d + a] = std::max(n[d + a], b[d + a]);
        }
  }
}

template <int D>
void RowScreen::flag_rows(const double* u, const double* H, double limit) {
  // One value per row in a loop without branches or pushes (it vectorizes); the caller
  // collects the flagged rows.
  const int d = D > 0 ? D : d_;
  const std::size_t cells_stride = 2 * static_cast<std::size_t>(d);
#pragma omp for schedule(static)
  for (std::size_t i = 0; i < particles_; ++i) {
    const double* n = near_.data() + cell_of_[i] * cells_stride;
    double reach2 = 0.0, dh2 = 0.0;
    for (int a = 0; a < d; ++a) {
      const double du = u[i * d + a] - u0_[i * d + a];
      const double far = std::max(n[d + a] - du, du - n[a]);
      reach2 += far * far;
    }
    if (H)
      for (int a = 0; a < d * d; ++a) {
        const double e = H[i * d * d + a] - H0_[i * d * d + a];
        dh2 += e * e;
      }
    // A row without bonds has 1 / shortest = 0: only its H term (and nothing to read).
    flag_[i] = r_[i] + std::sqrt(reach2) * inverse_shortest_[i] + std::sqrt(dh2) >= limit;
  }
}

std::vector<ParticleId> RowScreen::rows_reaching(const double* u, const double* H, double threshold) {
  if (!taken()) throw std::logic_error("RowScreen::rows_reaching before take()");
  if ((H == nullptr) != H0_.empty()) throw std::logic_error("RowScreen::rows_reaching: H given unlike take()");
  const std::size_t cells = cell_begin_.size() - 1;
  box_.resize(cells * 2 * d_);
  near_.resize(cells * 2 * d_);
  flag_.resize(particles_);
  const double limit = threshold * (1.0 - 1e-6);
  std::vector<std::vector<ParticleId>> found;
#pragma omp parallel
  {
#pragma omp single
    found.resize(static_cast<std::size_t>(omp_get_num_threads()));
    cell_boxes(u);
    if (d_ == 2) flag_rows<2>(u, H, limit);
    else if (d_ == 3) flag_rows<3>(u, H, limit);
    else flag_rows<0>(u, H, limit);
    std::vector<ParticleId>& mine = found[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < particles_; ++i)
      if (flag_[i]) mine.push_back(static_cast<ParticleId>(i));
  }
  std::vector<ParticleId> out;
  for (auto& f : found) out.insert(out.end(), f.begin(), f.end());
  return out;
}

std::vector<ParticleId> RowScreen::rows_at_snapshot(double threshold) const {
  if (!taken()) throw std::logic_error("RowScreen::rows_at_snapshot before take()");
  const double limit = threshold * (1.0 - 1e-6);
  std::vector<ParticleId> out;
  for (std::size_t i = 0; i < particles_; ++i)
    if (r_[i] >= limit) out.push_back(static_cast<ParticleId>(i));
  return out;
}

}  // namespace perinom::detail

#include "perinom/operators/scalar_csr.hpp"

#include <algorithm>
#include <stdexcept>

namespace perinom {
namespace {

template <int NC>
void gather(const ScalarCsr& a, const double* u, double* out) {
  const std::size_t n = a.rows();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double acc[NC] = {};
    for (Offset k = a.offsets[i]; k < a.offsets[i + 1]; ++k) {
      const double* uj = u + static_cast<std::size_t>(a.cols[k]) * NC;
      for (int c = 0; c < NC; ++c) acc[c] += a.values[k] * uj[c];
    }
    for (int c = 0; c < NC; ++c) out[i * NC + c] += acc[c];
  }
}

}  // namespace

std::size_t ScalarCsr::memory_bytes() const {
  return offsets.size() * sizeof(Offset) + cols.size() * sizeof(ParticleId) +
         values.size() * sizeof(double);
}

void ScalarCsr::apply_add(const double* u, int nc, double* out) const {
  switch (nc) {
    case 1: return gather<1>(*this, u, out);
    case 2: return gather<2>(*this, u, out);
    case 3: return gather<3>(*this, u, out);
    default:
      for (int c = 0; c < nc; ++c)
        for (std::size_t i = 0; i < rows(); ++i)
          for (Offset k = offsets[i]; k < offsets[i + 1]; ++k)
            out[i * nc + c] += values[k] * u[static_cast<std::size_t>(cols[k]) * nc + c];
  }
}

double ScalarCsr::at(std::size_t i, std::size_t j) const {
  const auto first = cols.begin() + offsets[i], last = cols.begin() + offsets[i + 1];
  const auto it = std::lower_bound(first, last, static_cast<ParticleId>(j));
  return (it != last && *it == static_cast<ParticleId>(j)) ? values[it - cols.begin()] : 0.0;
}

ScalarCsr assemble_rows(std::size_t n, const std::function<void(std::size_t, RowAccumulator&)>& add_row) {
  std::vector<std::vector<ParticleId>> row_cols(n);
  std::vector<std::vector<double>> row_vals(n);
  for_each_block_row(n, n, 1, [&add_row] { return add_row; },
                     [&](std::size_t r, const std::vector<ParticleId>& cols, const std::vector<double>& values) {
                       row_cols[r] = cols;
                       row_vals[r] = values;
                     });
  ScalarCsr A;
  A.offsets.assign(n + 1, 0);
  for (std::size_t r = 0; r < n; ++r) A.offsets[r + 1] = A.offsets[r] + row_cols[r].size();
  for (std::size_t r = 0; r < n; ++r) {
    A.cols.insert(A.cols.end(), row_cols[r].begin(), row_cols[r].end());
    A.values.insert(A.values.end(), row_vals[r].begin(), row_vals[r].end());
  }
  return A;
}

void reassemble_rows(ScalarCsr& A, const std::vector<ParticleId>& rows,
                     const std::function<void(std::size_t, RowAccumulator&)>& add_row) {
  bool outside = false;
#pragma omp parallel if (rows.size() > 64)
  {
    RowAccumulator acc(A.rows(), 1);
#pragma omp for schedule(dynamic, 16) reduction(|| : outside)
    for (std::size_t q = 0; q < rows.size(); ++q) {
      const std::size_t r = rows[q];
      add_row(r, acc);
      acc.finish();
      const auto first = A.cols.begin() + A.offsets[r], last = A.cols.begin() + A.offsets[r + 1];
      std::fill(A.values.begin() + A.offsets[r], A.values.begin() + A.offsets[r + 1], 0.0);
      // Both rows are sorted: one merge.
      auto it = first;
      for (std::size_t k = 0; k < acc.cols().size(); ++k) {
        it = std::lower_bound(it, last, acc.cols()[k]);
        if (it == last || *it != acc.cols()[k]) {
          outside = outside || *acc.block(k) != 0.0;
          continue;
        }
        A.values[it - A.cols.begin()] = *acc.block(k);
      }
      acc.clear();
    }
  }
  if (outside) throw std::logic_error("reassemble_rows: a refreshed row has an entry outside the stored pattern");
}

}  // namespace perinom

#pragma once
/// @file A scalar sparse matrix in CSR form, applied to every component of a vector field.
#include <cstddef>
#include <functional>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/operators/row_accumulator.hpp"

namespace perinom {

/// N x N scalar matrix A, used as A (x) I_nc on fields of nc components per particle.
struct ScalarCsr {
  std::vector<Offset> offsets{0};
  std::vector<ParticleId> cols;  ///< sorted within each row
  std::vector<double> values;

  std::size_t rows() const { return offsets.size() - 1; }
  std::size_t nonzeros() const { return cols.size(); }
  std::size_t memory_bytes() const;
  /// out[i*nc + c] += sum_j A_ij u[j*nc + c] (a gather; deterministic).
  void apply_add(const double* u, int nc, double* out) const;
  /// A_ij, or 0 if (i, j) is not stored.
  double at(std::size_t i, std::size_t j) const;
};

/// Assembles an n x n ScalarCsr row by row, in parallel: add_row(r, acc) adds row r's
/// entries to acc (a RowAccumulator with one value per column; columns may repeat).
ScalarCsr assemble_rows(std::size_t n, const std::function<void(std::size_t, RowAccumulator&)>& add_row);

/// Recomputes the listed rows of A in place with add_row (as assemble_rows), keeping A's
/// pattern: entries the new row lacks become zero. Throws std::logic_error when a new row
/// has a column outside the pattern (a refresh after broken bonds only removes couplings).
void reassemble_rows(ScalarCsr& A, const std::vector<ParticleId>& rows,
                     const std::function<void(std::size_t, RowAccumulator&)>& add_row);

}  // namespace perinom

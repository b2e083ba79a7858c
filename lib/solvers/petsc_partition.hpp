#pragma once
/// @file PT-Scotch through PETSc's MatPartitioning, in the PETSc module (internal to
/// lib/solvers).
#include <cstddef>
#include <cstdint>

namespace perinom::detail {

/// Parts for the n vertices of a symmetric graph without self-loops (CSR: offsets, cols),
/// computed on this process alone; rank_of[i] in 0..parts-1.
void partition_graph(std::size_t n, const std::int64_t* offsets, const std::int32_t* cols, int parts, int* rank_of);

}  // namespace perinom::detail

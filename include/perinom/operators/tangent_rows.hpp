#pragma once
/// @file Block rows of the stiffness K = G^T (V . C) G + S0 (x) I (THEORY sec. 3-4).
#include <cstdint>
#include <functional>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
#include "perinom/operators/row_accumulator.hpp"
#include "perinom/operators/stabilization_term.hpp"

namespace perinom {

/// The pointwise tangent: C_m = dP/dF at particle m as d^4 values C[((a*d + b)*d + c)*d + e]
/// = dP_ab / dF_ce, times V_m. stride is 0 when every particle shares one C (then only
/// the volumes differ), d^4 otherwise.
struct PointwiseTangent {
  const double* C = nullptr;
  std::size_t stride = 0;
  const double* volume = nullptr;
};

/// Rows in the strong form (THEORY sec. 5): f_i = -V_i [sum_m G[i][m] P_m - P_i m_i] for the
/// particles with in_band[i] = 1, m_i = normal_over_h (dim values per particle).
struct StrongRows {
  const std::uint8_t* in_band = nullptr;
  const double* normal_over_h = nullptr;
};

/// Visits every block row i of K: visit(i, cols, blocks), blocks holding one row-major
/// d x d block per column (K_(i a),(j c) = blocks[k*d*d + a*d + c] for j = cols[k]).
/// K_(i),(j) = sum_m V_m sum_(b,e) G_b[m][i] C_m[a b c e] G_e[m][j] over m in {i} + H'_i
/// and j in {m} + H_m, plus S0_ij on the block diagonal; a strong row (when `strong` is
/// given) takes its sources from row i of G instead: -V_i G_b[i][m] for m in {i} + H_i,
/// plus V_i m_i[b] at m = i. Rows are computed in parallel;
/// visit is called concurrently from several threads with distinct i.
/// Cost: sum over m in {i} + H'_i of |H_m| d^3 per row. S (any level, or null) adds its rows
/// of S0 on the diagonals of the blocks.
/// `local` (N x d^3, or null) adds a term of row i that depends on grad u at i alone:
/// K_(i a),(j c) += sum_e local_i[(a d + c) d + e] G_e[i][j] for j in {i} + H_i (follower
/// pressures).
void for_each_tangent_row(
    const NonlocalOperator& G, const PointwiseTangent& tangent, const StabilizationTerm* S,
    const BlockRowVisitor& visit, const StrongRows* strong = nullptr, const double* local = nullptr);
/// The same for the listed rows only (distinct): the columns come sorted only if asked (sums
/// over a row need no order), and a stored S0 (the assembled level) is read as stored, not
/// taken from its closed form (the same entries to rounding, at a fraction of the cost).
void for_each_tangent_row(const std::vector<ParticleId>& rows, const NonlocalOperator& G,
                          const PointwiseTangent& tangent, const StabilizationTerm* S, const BlockRowVisitor& visit,
                          bool sorted = false);

}  // namespace perinom

#pragma once
/// @file Parallel loops whose sums do not depend on the thread count.
#include <array>
#include <cstddef>

namespace perinom {

/// Below this many elements a loop runs on the calling thread: waking the team costs more
/// than the loop. Measured on the 2-core development machine: an empty parallel region
/// costs 4 us (21 us with OMP_WAIT_POLICY=PASSIVE), a serial pass over 300 doubles 0.06 us.
constexpr std::size_t parallel_minimum = 16384;

/// Visits k = 0..n-1 in 64 fixed contiguous blocks, in parallel; body(k, acc) may update
/// element k of any vector and add to the K partial sums acc. Each block is summed in order
/// and the blocks are added in order, so the sums are the same for any number of threads.
template <int K, class Body>
std::array<double, K> parallel_sums(std::size_t n, Body&& body) {
  constexpr int blocks = 64;
  double part[blocks][K] = {};
#pragma omp parallel for schedule(static) if (n >= parallel_minimum)
  for (int b = 0; b < blocks; ++b) {
    const std::size_t lo = n * b / blocks, hi = n * (b + 1) / blocks;
    double acc[K] = {};
    for (std::size_t k = lo; k < hi; ++k) body(k, acc);
    for (int c = 0; c < K; ++c) part[b][c] = acc[c];
  }
  std::array<double, K> sum{};
  for (int b = 0; b < blocks; ++b)
    for (int c = 0; c < K; ++c) sum[c] += part[b][c];
  return sum;
}

/// Visits k = 0..n-1 in parallel (element-wise updates only), when n is large enough.
template <class Body>
void parallel_for(std::size_t n, Body&& body) {
#pragma omp parallel for schedule(static) if (n >= parallel_minimum)
  for (std::size_t k = 0; k < n; ++k) body(k);
}

}  // namespace perinom

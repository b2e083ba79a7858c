#include "perinom/distributed/graph_partition.hpp"

#include <algorithm>
#include <stdexcept>

#include "../solvers/petsc_plugin.hpp"

namespace perinom {

std::vector<int> scotch_partition(const Families& f, int ranks) {
  if (ranks < 1) throw std::invalid_argument("scotch_partition: ranks < 1");
  const detail::PetscPlugin& p = detail::petsc_plugin("a PT-Scotch partition");
  const std::size_t n = f.particles();
  if (ranks == 1) return std::vector<int>(n, 0);
  // The symmetric graph: each family with its dual support, sorted, without repeats.
  const DualSupport dual = dual_support(f);
  std::vector<std::int64_t> offsets(n + 1, 0);
  std::vector<std::int32_t> cols;
  cols.reserve(2 * f.bonds());
  std::vector<std::int32_t> row;
  for (std::size_t i = 0; i < n; ++i) {
    row.assign(f.neighbors.begin() + f.begin(i), f.neighbors.begin() + f.end(i));
    row.insert(row.end(), dual.neighbors.begin() + dual.offsets[i], dual.neighbors.begin() + dual.offsets[i + 1]);
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    cols.insert(cols.end(), row.begin(), row.end());
    offsets[i + 1] = static_cast<std::int64_t>(cols.size());
  }
  std::vector<int> rank_of(n, 0);
  p.partition_graph(n, offsets.data(), cols.data(), ranks, rank_of.data());
  return rank_of;
}

}  // namespace perinom

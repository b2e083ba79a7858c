#include "perinom/operators/row_accumulator.hpp"

namespace perinom {

namespace {

// Rows row_of(0) .. row_of(count - 1), in parallel, each thread with its own fill and
// accumulator. Chunks of 8 rows: a row costs microseconds, and the short lists of rows a
// break refreshes (tens of rows) still spread over the threads.
template <class RowOf>
void block_rows(std::size_t count, RowOf row_of, std::size_t columns, int block,
                const std::function<RowFill()>& make_fill, const BlockRowVisitor& visit, bool sorted) {
#pragma omp parallel
  {
    RowAccumulator acc(columns, block);
    const RowFill fill = make_fill();
    std::vector<double> blocks;
#pragma omp for schedule(dynamic, 8)
    for (std::size_t r = 0; r < count; ++r) {
      const std::size_t i = row_of(r);
      fill(i, acc);
      acc.finish(sorted);
      blocks.resize(acc.cols().size() * block);
      for (std::size_t k = 0; k < acc.cols().size(); ++k)
        for (int c = 0; c < block; ++c) blocks[k * block + c] = acc.block(k)[c];
      visit(i, acc.cols(), blocks);
      acc.clear();
    }
  }
}

}  // namespace

void for_each_block_row(std::size_t rows, std::size_t columns, int block, const std::function<RowFill()>& make_fill,
                        const BlockRowVisitor& visit) {
  block_rows(rows, [](std::size_t r) { return r; }, columns, block, make_fill, visit, true);
}

void for_each_block_row(const std::vector<ParticleId>& rows, std::size_t columns, int block,
                        const std::function<RowFill()>& make_fill, const BlockRowVisitor& visit, bool sorted) {
  block_rows(rows.size(), [&rows](std::size_t r) { return static_cast<std::size_t>(rows[r]); }, columns, block,
             make_fill, visit, sorted);
}

}  // namespace perinom

#include "perinom/operators/row_accumulator.hpp"

namespace perinom {

void for_each_block_row(std::size_t rows, std::size_t columns, int block, const std::function<RowFill()>& make_fill,
                        const BlockRowVisitor& visit) {
#pragma omp parallel
  {
    RowAccumulator acc(columns, block);
    const RowFill fill = make_fill();
    std::vector<double> blocks;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t i = 0; i < rows; ++i) {
      fill(i, acc);
      acc.finish();
      blocks.resize(acc.cols().size() * block);
      for (std::size_t k = 0; k < acc.cols().size(); ++k)
        for (int c = 0; c < block; ++c) blocks[k * block + c] = acc.block(k)[c];
      visit(i, acc.cols(), blocks);
      acc.clear();
    }
  }
}

}  // namespace perinom

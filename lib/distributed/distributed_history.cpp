// DistributedModel as a ModelHistory over the ranks (distributed_model.hpp): the load path's
// plastic states on the owned particles, the ghosts kept equal to their owners.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "perinom/distributed/distributed_model.hpp"

namespace perinom {

ModelHistory& DistributedModel::local_history() const {
  ModelHistory* h = local_.history();
  if (!h) throw std::logic_error("DistributedModel: the local model keeps no history");
  return *h;
}

void DistributedModel::share_history(HistoryState state) {
  const std::size_t m = values_per_particle(), n = state.flags.size(), block = m + 1;
  if (!history_halo_) {
    shared_.assign(n * block, 0.0);
    const std::vector<std::int64_t> ghosts(part_.global.begin() + std::ptrdiff_t(part_.owned), part_.global.end());
    history_halo_ = std::make_unique<Halo>(part_.owned, ghosts, int(block), shared_.data());
  }
  for (std::size_t i = 0; i < part_.owned; ++i) {
    std::copy_n(state.values.begin() + std::ptrdiff_t(i * m), m, shared_.begin() + std::ptrdiff_t(i * block));
    shared_[i * block + m] = state.flags[i];
  }
  history_halo_->update();
  for (std::size_t i = part_.owned; i < n; ++i) {
    std::copy_n(shared_.begin() + std::ptrdiff_t(i * block), m, state.values.begin() + std::ptrdiff_t(i * m));
    state.flags[i] = static_cast<std::uint8_t>(shared_[i * block + m]);
  }
  local_history().restore_history(state);
}

void DistributedModel::set_history_mode(HistoryMode mode) { local_history().set_history_mode(mode); }

std::size_t DistributedModel::flag_violations(double tolerance) {
  const std::vector<std::uint8_t> before = local_history().save_history().flags;
  local_history().flag_violations(tolerance);
  HistoryState now = local_history().save_history();
  double count = 0.0;
  for (std::size_t i = 0; i < part_.owned; ++i) count += now.flags[i] && !before[i] ? 1.0 : 0.0;
  share_history(std::move(now));
  return static_cast<std::size_t>(sum_over_ranks(count));
}

std::vector<double> DistributedModel::history_variable() const {
  std::vector<double> xi = local_history().history_variable();
  xi.resize(part_.owned);
  return xi;
}

std::size_t DistributedModel::values_per_particle() const { return local_history().values_per_particle(); }

HistoryState DistributedModel::save_history() const {
  HistoryState s = local_history().save_history();
  s.values.resize(part_.owned * values_per_particle());
  s.flags.resize(part_.owned);
  return s;
}

void DistributedModel::restore_history(const HistoryState& mine) {
  const std::size_t m = values_per_particle();
  if (mine.flags.size() != part_.owned || mine.values.size() != part_.owned * m)
    throw std::invalid_argument("DistributedModel: the history holds " + std::to_string(mine.flags.size()) +
                                " particles, the rank owns " + std::to_string(part_.owned));
  HistoryState all = local_history().save_history();
  std::copy(mine.values.begin(), mine.values.end(), all.values.begin());
  std::copy(mine.flags.begin(), mine.flags.end(), all.flags.begin());
  share_history(std::move(all));
}

void DistributedModel::reset_history() { local_history().reset_history(); }

void DistributedModel::commit(const double* u) {
  local_history().commit(local_state(u).data());
  share_history(local_history().save_history());
}

void DistributedModel::begin_step() { local_history().begin_step(); }

void DistributedModel::commit_trial() {
  local_history().commit_trial();
  share_history(local_history().save_history());
}

}  // namespace perinom

#include "perinom/distributed/correction_share.hpp"

#include <algorithm>
#include <memory>

#include "perinom/distributed/ranks.hpp"

namespace perinom {
namespace {

/// A Halo over scratch of its own: a field is copied in (owned values), updated, and its
/// ghosts copied out.
struct ScalarHalo {
  explicit ScalarHalo(const LocalPart& part)
      : owned(part.owned), values(part.particles.size(), 0.0),
        halo(part.owned, std::vector<std::int64_t>(part.global.begin() + std::ptrdiff_t(part.owned), part.global.end()),
             1, values.data()) {}
  void exchange(double* field) {
    std::copy(field, field + owned, values.begin());
    halo.update();
    std::copy(values.begin() + std::ptrdiff_t(owned), values.end(), field + owned);
  }
  std::size_t owned;
  std::vector<double> values;
  Halo halo;
};

}  // namespace

CorrectionShare correction_share(const LocalPart& part) {
  CorrectionShare share;
  share.owned = part.owned;
  share.near = part.near;
  auto halo = std::make_shared<ScalarHalo>(part);
  share.exchange = [halo](double* field) { halo->exchange(field); };
  share.sum = [](double* values, int count) { sum_over_ranks(values, count); };
  share.max = [](double* values, int count) { max_over_ranks(values, count); };
  return share;
}

}  // namespace perinom

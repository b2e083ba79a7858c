#include "perinom/fracture/bond_breaking.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "bond_selection.hpp"
#include "row_screen.hpp"
#include "perinom/fracture/bond_measures.hpp"
#include "perinom/materials/measures.hpp"

namespace perinom {

bool parse_damage_criterion(const std::string& name, DamageCriterion& c) {
  if (name == "instability") c = DamageCriterion::instability;
  else if (name == "stretch") c = DamageCriterion::stretch;
  else if (name == "stress") c = DamageCriterion::stress;
  else return false;
  return true;
}

BondBreaking::BondBreaking(CorrespondenceModel& model, const PointCloud& cloud, DamageCriterion criterion,
                           double parameter)
    : model_(&model), cloud_(&cloud), criterion_(criterion), parameter_(parameter) {
  if (!(parameter > 0.0)) throw std::invalid_argument("BondBreaking: the criterion's parameter must be positive");
  if (criterion == DamageCriterion::instability) instability_.emplace(parameter);
  screen(true);
}

BondBreaking::~BondBreaking() = default;

void BondBreaking::screen(bool on) {
  // The stress criterion compares per-particle values: nothing to screen.
  if (criterion_ == DamageCriterion::stress) on = false;
  if (on && !screen_) screen_ = std::make_unique<detail::RowScreen>(*cloud_, model_->G().graph());
  if (!on) screen_.reset();
  screened_measure_ = 0, skip_ = 0, backoff_ = 0;
}

// The rows that can hold a bond whose measure, sqrt(squared(i, j)), reaches `level`: from the
// screen's snapshot of that measure, taken anew (a pass over every bond) when there is none or
// when the rows kept pass an eighth of all. Every row when screening is off, and for a while
// when it does not pay: a snapshot that lasted fewer than 16 calls (fast, large motion, an
// impact) reads every row for the next 32, 64, ... 512 calls instead (the old cost, not a
// snapshot and a bound a step), then tries a snapshot again.
template <class Squared>
const std::vector<ParticleId>& BondBreaking::rows_near(int measure, const Squared& squared, const double* u,
                                                       const double* H, double level) {
  const BondGraph& g = model_->G().graph();
  auto every_row = [&]() -> const std::vector<ParticleId>& {
    if (all_rows_.size() != g.rows()) {
      all_rows_.resize(g.rows());
      for (std::size_t i = 0; i < all_rows_.size(); ++i) all_rows_[i] = static_cast<ParticleId>(i);
    }
    return all_rows_;
  };
  if (!screen_) return every_row();
  if (skip_ > 0) {
    --skip_;
    return every_row();
  }
  ++since_snapshot_;
  if (screened_measure_ == measure) {
    rows_ = screen_->rows_reaching(u, H, level);
    if (rows_.size() * 8 <= g.rows()) return rows_;
    if (since_snapshot_ < 16) {
      backoff_ = std::min(2 * std::max(backoff_, 16), 512);
      skip_ = backoff_ - 1;
      screened_measure_ = 0;
      return every_row();
    }
    backoff_ = 0;
  }
  std::vector<double> top = detail::live_row_maxima(g, squared);
  for (double& t : top) t = std::sqrt(t);
  screen_->take(u, H, std::move(top));
  screened_measure_ = measure;
  since_snapshot_ = 0;
  rows_ = screen_->rows_at_snapshot(level);
  return rows_;
}

void BondBreaking::hold(const std::vector<ParticleId>& particles) {
  held_.resize(cloud_->size(), 0);
  for (const ParticleId i : particles) held_.at(i) = 1;
}

std::size_t BondBreaking::find(const double* u, const double* H) {
  if (CohesiveBonds* softening = model_->cohesive()) softening->commit(u);  // the balanced state's openings
  using detail::live_bonds_where;
  using detail::live_maximum;
  const BondGraph& g = model_->G().graph();
  const int d = cloud_->dim;
  const double* x = cloud_->x.data();
  due_.clear();
  ++finds_;
  auto gradient = [&] {  // from G only when the caller has none, and only when needed
    if (!H) {
      H_.resize(cloud_->size() * d * d);
      model_->gradient(u, H_.data());
      H = H_.data();
    }
    return H;
  };
  // The bond passes, with the dimension a compile-time constant where it is 2 or 3. Squares
  // are compared (no root per bond); the stretch and hourglass strain themselves are roots of
  // the largest squares. Only the rows the screen keeps are read: the stretch ratio
  // |xi + eta| / |xi| (measure 1) is screened without grad u, the hourglass strain (2) with it.
  // Bonds that never break (no-fail zones) neither arm the instability criterion nor set
  // s_hg_max, nor keep a row in the screen.
  enum : int { stretch_ratio = 1, hourglass_strain = 2 };
  auto breakable = [&](std::size_t i, std::size_t j) { return held_.empty() || !(held_[i] || held_[j]); };
  auto pass = [&](auto dim) {
    const BondStretch stretch{dim, x, u};
    auto ratio = [&](std::size_t i, std::size_t j) { return breakable(i, j) ? stretch.squared_ratio(i, j) : 0.0; };
    if (criterion_ == DamageCriterion::stretch) {
      const auto& rows = rows_near(stretch_ratio, ratio, u, nullptr, 1.0 + parameter_);
      due_ = live_bonds_where(g, rows, [&](std::size_t i, std::size_t j) { return stretch.exceeds(i, j, parameter_); });
      return;
    }
    // Instability, one pass a step: the largest stretch until armed (and at that step the
    // largest hourglass strain, once; none exceeds it then), afterwards the hourglass strains.
    if (!instability_->armed()) {
      const auto& rows = rows_near(stretch_ratio, ratio, u, nullptr, 1.0 + instability_->s_max());
      const bool armed = instability_->arm(std::sqrt(live_maximum(g, rows, ratio)) - 1.0, [&] {
        const HourglassStrain hourglass{dim, x, u, gradient()};
        return std::sqrt(
            live_maximum(g, [&](std::size_t i, std::size_t j) { return breakable(i, j) ? hourglass.squared(i, j) : 0.0; }));
      });
      if (armed) armed_find_ = finds_;
      return;
    }
    const HourglassStrain hourglass{dim, x, u, gradient()};
    const double t = instability_->threshold();
    auto squared = [&](std::size_t i, std::size_t j) { return breakable(i, j) ? hourglass.squared(i, j) : 0.0; };
    const auto& rows = rows_near(hourglass_strain, squared, u, hourglass.H, t);
    due_ = live_bonds_where(g, rows, [&](std::size_t i, std::size_t j) { return hourglass.exceeds(i, j, t); });
  };
  if (criterion_ == DamageCriterion::stress) {
    sigma_.resize(cloud_->size() * 9);
    model_->law().cauchy(gradient(), sigma_.data());  // CorrespondenceModel::stress3 at grad u
    sigma1_.resize(cloud_->size());
    for (std::size_t i = 0; i < sigma1_.size(); ++i) sigma1_[i] = max_principal_stress(sigma_.data() + i * 9);
    const double* s1 = sigma1_.data();
    const double f_t = parameter_;
    auto over = [s1, f_t](std::size_t i, std::size_t j) { return 0.5 * (s1[i] + s1[j]) > f_t; };
    if (const CohesiveBonds* softening = model_->cohesive()) {
      // With softening bonds a bond over f_t leaves the operators when it is opened to its
      // law's peak, or when both its particles have such a bond now (docs/theory.md,
      // "Softening bonds": a bond beside a crack stays in the body; without this gate the
      // notched peak moved 21% over a halving of the spacing).
      auto opened = [&](std::size_t i, std::size_t j) {
        return over(i, j) && breakable(i, j) && softening->at_peak(ParticleId(i), ParticleId(j), u);
      };
      cracking_.assign(cloud_->size(), 0);
      for (const BondPair& b : live_bonds_where(g, opened)) cracking_[b.first] = cracking_[b.second] = 1;
      const char* cracking = cracking_.data();
      due_ = live_bonds_where(g, [&, cracking](std::size_t i, std::size_t j) {
        return over(i, j) && ((cracking[i] && cracking[j]) || softening->at_peak(ParticleId(i), ParticleId(j), u));
      });
    } else {
      due_ = live_bonds_where(g, over);
    }
  } else if (d == 2) {
    pass(std::integral_constant<int, 2>{});
  } else if (d == 3) {
    pass(std::integral_constant<int, 3>{});
  } else {
    pass(d);
  }
  if (!held_.empty())
    due_.erase(std::remove_if(due_.begin(), due_.end(), [&](const BondPair& b) { return held_[b.first] || held_[b.second]; }),
               due_.end());
  return due_.size();
}

double BondBreaking::stable_time_step() {
  if (row_sums_.empty()) {
    row_sums_ = model_->stiffness_row_sums();
    mass_ = model_->lumped_mass();
    largest_ratio();
  }
  return 2.0 / std::sqrt(w2_);
}

void BondBreaking::largest_ratio() {
  w2_ = 0.0, w2_at_ = 0;
  for (std::size_t k = 0; k < row_sums_.size(); ++k)
    if (row_sums_[k] / mass_[k] > w2_) w2_ = row_sums_[k] / mass_[k], w2_at_ = k;
}

std::size_t BondBreaking::apply() {
  if (due_.empty()) return 0;
  const BondBreaks b = model_->break_bonds(due_);
  died_.insert(died_.end(), due_.begin(), due_.end());
  groups_.push_back(due_.size());
  due_.clear();
  return account(b);
}

BondBreaks BondBreaking::apply(const double* u, double* f) {
  if (due_.empty()) return {};
  BondBreaks b = model_->break_bonds(due_, u, f);
  died_.insert(died_.end(), due_.begin(), due_.end());
  groups_.push_back(due_.size());
  due_.clear();
  b.broken = account(b);
  return b;
}

// state(): broken, finds, armed find, armed (0/1), s_hg_max, the number of groups, then each
// group as its size and its bonds' ends in pairs; with softening bonds, then their committed
// openings (one per broken bond, in the order broken).
std::vector<double> BondBreaking::state() const {
  std::vector<double> s{double(broken_), double(finds_), double(armed_find_),
                        instability_ && instability_->armed() ? 1.0 : 0.0, hourglass_threshold(), double(groups_.size())};
  s.reserve(s.size() + groups_.size() + 2 * died_.size());
  std::size_t at = 0;
  for (const std::size_t n : groups_) {
    s.push_back(double(n));
    for (std::size_t k = at; k < at + n; ++k) s.push_back(double(died_[k].first)), s.push_back(double(died_[k].second));
    at += n;
  }
  if (const CohesiveBonds* softening = model_->cohesive()) {
    const std::vector<double> k = softening->kappas();
    s.insert(s.end(), k.begin(), k.end());
  }
  return s;
}

void BondBreaking::restore(const std::vector<double>& s) {
  const auto bad = [](const std::string& what) { return std::invalid_argument("BondBreaking::restore: " + what); };
  if (broken_ != 0 || !died_.empty()) throw bad("bonds were broken already");
  if (s.size() < 6) throw bad("the state is too short");
  if (s[3] != 0.0 && !instability_) throw bad("the state is the instability criterion's, this run's is not");
  const double n = double(cloud_->size());
  const auto whole = [](double x, double below) { return x >= 0.0 && x < below && x == std::floor(x); };
  if (!whole(s[5], double(s.size()))) throw bad("the state's group count does not fit it");
  // Every group checked before any is broken: a state that does not fit changes nothing.
  std::size_t at = 6;
  for (std::size_t g = 0; g < std::size_t(s[5]); ++g) {
    if (at >= s.size() || !whole(s[at], double(s.size())) || at + 1 + 2 * std::size_t(s[at]) > s.size())
      throw bad("a group runs past the end of the state");
    for (std::size_t k = at + 1; k < at + 1 + 2 * std::size_t(s[at]); ++k)
      if (!whole(s[k], n)) throw bad("the state names a particle beyond the cloud");
    at += 1 + 2 * std::size_t(s[at]);
  }
  if (!whole(s[0], double(s.size()) + 1.0)) throw bad("the state's count of broken bonds does not fit it");
  CohesiveBonds* softening = model_->cohesive();
  const std::size_t groups_end = at, openings = softening ? std::size_t(s[0]) : 0;
  if (softening && softening->size() != 0) throw bad("bonds soften already");
  if (s.size() - at != openings)
    throw bad(softening ? "the state does not hold one opening per softening bond" : "the state has values after its last group");
  // The row sums as a run keeps them: summed over every row of the model as built, then
  // updated on the rows each group changes (a sum over every row at the end would differ in
  // the last bits: its rows are accumulated in another order).
  stable_time_step();
  at = 6;
  for (std::size_t g = 0; g < std::size_t(s[5]); ++g) {
    due_.clear();
    for (std::size_t k = at + 1; k < at + 1 + 2 * std::size_t(s[at]); k += 2)
      due_.emplace_back(ParticleId(s[k]), ParticleId(s[k + 1]));
    at += 1 + 2 * std::size_t(s[at]);
    apply();
  }
  if (broken_ != std::size_t(s[0])) throw bad("the recorded bonds do not match its count");
  if (softening) softening->restore_kappas(std::vector<double>(s.begin() + groups_end, s.end()));
  finds_ = std::int64_t(s[1]), armed_find_ = std::int64_t(s[2]);
  if (s[3] != 0.0) instability_->rearm(s[4]);
  screen(screen_ != nullptr);  // a fresh snapshot: the same bonds, found anew
}

std::size_t BondBreaking::account(const BondBreaks& b) {
  if (!row_sums_.empty()) {
    // A refreshed row m of G and S changes the stiffness rows of m and of its family.
    const BondGraph& g = model_->G().graph();
    std::vector<ParticleId> rows = b.rows;
    for (const ParticleId m : b.rows)
      for (Offset k = g.begin(m); k < g.end(m); ++k) rows.push_back(g.col(k));
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    const std::vector<double> sums = model_->stiffness_row_sums(rows);
    // The largest ratio follows the changed rows; only when its own row fell is every row read.
    const int d = cloud_->dim;
    bool fell = false;
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int a = 0; a < d; ++a) {
        const std::size_t k = rows[r] * d + a;
        row_sums_[k] = sums[r * d + a];
        const double w2 = row_sums_[k] / mass_[k];
        if (w2 > w2_) w2_ = w2, w2_at_ = k, fell = false;
        else if (k == w2_at_ && w2 < w2_) fell = true;
      }
    if (fell) largest_ratio();
  }
  broken_ += b.broken;
  detached_ = b.detached.size();
  return b.broken;
}

}  // namespace perinom

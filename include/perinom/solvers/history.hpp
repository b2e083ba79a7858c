#pragma once
/// @file A solver's iteration history, and the observers of intermediate states: snapshots
/// (Observer) and checkpoints (Checkpoints).
#include <algorithm>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

namespace perinom {

/// Named columns, one row per recorded iteration, stored flat (row-major) so recording a
/// row inside a time loop does not allocate once reserve() has made room for it.
struct History {
  std::vector<std::string> columns;
  std::vector<double> values;

  std::size_t rows() const { return columns.empty() ? 0 : values.size() / columns.size(); }
  double at(std::size_t row, std::size_t column) const { return values[row * columns.size() + column]; }
  std::vector<double> row(std::size_t r) const {
    return {values.begin() + r * columns.size(), values.begin() + (r + 1) * columns.size()};
  }
  void add(std::initializer_list<double> row) { values.insert(values.end(), row); }
  /// The index of the column `name`. @throws std::out_of_range if there is none.
  std::size_t column(const std::string& name) const {
    const auto at = std::find(columns.begin(), columns.end(), name);
    if (at == columns.end()) throw std::out_of_range("History: no column '" + name + "'");
    return static_cast<std::size_t>(at - columns.begin());
  }
  /// Room for `rows` rows, at most 65,536 (a run recording more grows by doubling).
  void reserve(std::int64_t rows) {
    values.reserve(static_cast<std::size_t>(std::min<std::int64_t>(std::max<std::int64_t>(rows, 0), 65536)) *
                   columns.size());
  }
};

/// Called with (iteration or step, load factor or time, u) every `every` iterations
/// (never when every = 0), for snapshots.
struct Observer {
  std::int64_t every = 0;
  std::function<void(std::int64_t, double, const std::vector<double>&)> call;
  void operator()(std::int64_t it, double t, const std::vector<double>& u) const {
    if (every > 0 && call && it % every == 0) call(it, t, u);
  }
};

/// Called with the solver's whole state (AdrState, VerletState, LoadPathState) every `every`
/// iterations, steps or load steps (never when every = 0), for checkpoints the solver can
/// resume from bit for bit. What is done with the state (a file) is the caller's business.
template <class State>
struct Checkpoints {
  std::int64_t every = 0;
  std::function<void(const State&)> call;
  bool due(std::int64_t it) const { return every > 0 && call && it % every == 0; }
};

}  // namespace perinom

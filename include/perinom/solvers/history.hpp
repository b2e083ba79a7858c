#pragma once
/// @file A solver's iteration history, and an observer of intermediate states.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace perinom {

/// Named columns, one row per recorded iteration.
struct History {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
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

}  // namespace perinom

#pragma once
// A position as the notes print it: "0.05, 0.01" (%g per coordinate).
#include <cstdio>
#include <string>

namespace perinom::cli {

inline std::string point_text(const double* x, int d) {
  std::string out;
  for (int a = 0; a < d; ++a) {
    char c[32];
    std::snprintf(c, sizeof c, "%s%g", a ? ", " : "", x[a]);
    out += c;
  }
  return out;
}

}  // namespace perinom::cli

#include "memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "perinom/core/error.hpp"
#include "perinom/scene/registry.hpp"

namespace perinom::cli {
namespace {

/// Bonds of radius families on an n[0] x n[1] (x n[2]) lattice of spacings h within delta:
/// each offset o within delta joins prod_a (n_a - |o_a|) ordered pairs. Above 10^7 offsets
/// (a horizon of hundreds of spacings) the ball's volume over the cell's stands in for the count.
double lattice_bonds(const double n[3], const double h[3], int d, double delta) {
  double r[3] = {0, 0, 0}, offsets = 1.0, cell = 1.0, total = 1.0;
  for (int a = 0; a < d; ++a) {
    r[a] = std::min(std::floor(delta / h[a]), n[a]);
    offsets *= 2.0 * r[a] + 1.0, cell *= h[a], total *= n[a];
  }
  if (offsets > 1e7) {
    const double ball = d == 2 ? M_PI * delta * delta : 4.0 / 3.0 * M_PI * delta * delta * delta;
    return total * std::min(ball / cell, total - 1.0);
  }
  double bonds = 0.0;
  const long rz = d == 3 ? static_cast<long>(r[2]) : 0;
  for (long k = -rz; k <= rz; ++k)
    for (long j = -static_cast<long>(r[1]); j <= static_cast<long>(r[1]); ++j)
      for (long i = -static_cast<long>(r[0]); i <= static_cast<long>(r[0]); ++i) {
        if (i == 0 && j == 0 && k == 0) continue;
        const double x = i * h[0], y = j * h[1], z = k * h[2];
        if (x * x + y * y + z * z > delta * delta) continue;
        double pairs = (n[0] - std::abs(i)) * (n[1] - std::abs(j));
        if (d == 3) pairs *= n[2] - std::abs(k);
        bonds += std::max(pairs, 0.0);
      }
  return bonds;
}

/// The share of the box the holes take (overlaps and parts outside the box ignored).
double hole_fraction(const BoxGeometry& g) {
  double box = 1.0, holes = 0.0;
  for (int a = 0; a < g.dim; ++a) box *= g.max[a] - g.min[a];
  for (const auto& h : g.holes) {
    if (h.shape == Hole::Shape::circle) holes += M_PI * h.radius * h.radius;
    else if (h.shape == Hole::Shape::sphere) holes += 4.0 / 3.0 * M_PI * std::pow(h.radius, 3);
    else holes += M_PI * h.radius * h.radius * (g.max[h.axis] - g.min[h.axis]);
  }
  return std::clamp(holes / box, 0.0, 0.95);
}

}  // namespace

MemoryEstimate estimate_memory(const Scene& s) {
  MemoryEstimate e;
  if (s.body_files.given()) {
    e.known = false;
    e.baseline = e.bytes = peak_resident_bytes();
    return e;
  }
  const int d = s.dim;
  const double dx = s.discretization.dx;
  const MemoryRates rates = find_model(s.model.type)->memory(s);
  double n[3] = {1, 1, 1}, h[3] = {dx, dx, dx}, cells = 1.0;
  for (int a = 0; a < d; ++a) {
    const double length = s.geometry.max[a] - s.geometry.min[a];
    n[a] = std::max(1.0, std::round(length / dx));
    h[a] = length / n[a];
    if (rates.nodes_on_edges) n[a] += 1.0;
    cells *= n[a];
  }
  const double solid = 1.0 - hole_fraction(s.geometry);
  e.particles = cells * solid;
  if (s.discretization.horizon_neighbors > 0) {
    // More neighbours than particles is refused once the cloud exists; here it is all pairs.
    e.bonds = e.particles * std::min<double>(s.discretization.horizon_neighbors, std::max(e.particles - 1.0, 0.0));
    e.key = "discretization.horizon.neighbors";
  } else {
    e.bonds = lattice_bonds(n, h, d, s.discretization.horizon_ratio * dx) * solid;
    e.key = "discretization.horizon.ratio";
  }
  // Name the horizon when the families, not the lattice, are what is large.
  if (e.bonds < 500.0 * e.particles) e.key = "discretization.dx";
  // The model's measured peak bytes per bond and per particle (its registry row, MemoryRates).
  const double per_bond = rates.per_bond, per_particle = rates.per_particle;
  e.baseline = peak_resident_bytes();
  e.bytes = e.baseline + per_bond * e.bonds + per_particle * e.particles;
  e.bytes += jacobian_bytes(s, e.particles, e.bonds);
  return e;
}

double jacobian_bytes(const Scene& s, double particles, double bonds) {
  if (!solver_of(s).jacobian && s.solver.check != "newton") return 0.0;
  // The Jacobian couples particles up to two horizons apart: d^2 entries of 16 bytes (a
  // value and a 64-bit column) per pair, and the factors, counted as three times that. A
  // plate has one unknown per node, not d, but its factors fill more than three times its
  // matrix: counting one, a 40,401-node plate by MUMPS on 2 ranks was estimated at 168 MiB
  // per rank against 202 measured; with d^2 it is 357, so the rule keeps d^2 for plates.
  const int d = s.dim;
  const double reach = std::min(std::pow(2.0, d) * bonds / std::max(particles, 1.0), particles);
  return 4.0 * particles * reach * d * d * 16.0;
}

void require_memory(const Scene& s, const MemoryEstimate& e, double limit, bool limit_given) {
  const auto mib = [](double b) { return b / 1048576.0; };
  if (!e.known) {
    std::printf("perinom: %s: no estimate before building (a body from files: its size is in the file)\n", s.name.c_str());
    std::fflush(stdout);
    return;
  }
  std::printf("perinom: %s: estimate before building: %.4g particles, %.4g bonds, %.1f MiB\n", s.name.c_str(),
              e.particles, e.bonds, mib(e.bytes));
  std::fflush(stdout);
  if (limit <= 0.0 || e.bytes <= limit) return;
  char sizes[160];
  std::snprintf(sizes, sizeof sizes, "about %.0f MiB (%.4g particles, %.4g bonds), more than the %.3g MiB ",
                mib(e.bytes), e.particles, e.bonds, mib(limit));
  std::ostringstream what;
  what << e.key << ": the scene needs " << sizes
       << (limit_given ? "allowed by --max-memory" : "of memory available")
       << (e.key == "discretization.dx" ? "; use a larger dx" : "; use a smaller horizon")
       << (limit_given ? "" : " (--max-memory overrides the limit)");
  throw InputError(what.str());
}

}  // namespace perinom::cli

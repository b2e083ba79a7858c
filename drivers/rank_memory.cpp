#include "rank_memory.hpp"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "memory_estimate.hpp"
#include "perinom/core/error.hpp"
#include "perinom/distributed/ranks.hpp"
#include "perinom/scene/registry.hpp"

namespace perinom::cli {
namespace {

/// This host's name as a number a double holds exactly (52 bits of its hash).
double host_key() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return 0.0;
  return double(std::hash<std::string>{}(name) & ((std::uint64_t(1) << 52) - 1));
}

}  // namespace

RankMemory require_rank_memory(const Scene& s, double local_bonds, double local_particles, double max_memory) {
  const Ranks world = mpi_ranks();
  const MemoryRates rates = find_model(s.model.type)->memory(s);
  RankMemory m;
  // Measured (2026-12-03, docs/performance.md): with the consistent formulation a rank's peak
  // per local bond is 1.18 (2-D plate, 80k particles) and 1.22 (3-D bar, 128k) times the
  // serial rate, for reasons not found (the classical rate holds: 0.90 of the estimate on the
  // 3-D bar); the estimate takes 1.25 times the rate for it.
  const double distributed_rate = s.model.formulation == "consistent" ? 1.25 : 1.0;
  // Newton over the ranks: the rank's rows of the Jacobian and its share of the factors
  // (without it the estimate was half the peak: a 40,401-node plate by MUMPS on 2 ranks,
  // 103 MiB estimated, 202-204 MiB measured in two runs).
  m.rank_bytes = peak_resident_bytes() + distributed_rate * rates.per_bond * local_bonds + rates.per_particle * local_particles +
                 jacobian_bytes(s, local_particles, local_bonds);
  // Every rank's (host, estimate, available memory), on every rank: each fills its own row.
  std::vector<double> rows(std::size_t(3 * world.size), 0.0);
  rows[std::size_t(3 * world.rank)] = host_key();
  rows[std::size_t(3 * world.rank + 1)] = m.rank_bytes;
  rows[std::size_t(3 * world.rank + 2)] = available_memory();
  sum_over_ranks(rows.data(), int(rows.size()));
  std::map<double, double> host_need, host_room, host_ranks;
  int most = 0;
  for (int r = 0; r < world.size; ++r) {
    const double* row = &rows[std::size_t(3 * r)];
    host_need[row[0]] += row[1];
    host_ranks[row[0]] += 1.0;
    host_room[row[0]] = host_room.count(row[0]) ? std::min(host_room[row[0]], row[2]) : row[2];
    if (row[1] > rows[std::size_t(3 * most + 1)]) most = r;
  }
  m.most_bytes = rows[std::size_t(3 * most + 1)];
  double busiest = rows[0];
  for (const auto& [host, need] : host_need)
    if (need > host_need[busiest]) busiest = host;
  m.host_bytes = host_need[busiest];
  const auto mib = [](double b) { return b / 1048576.0; };
  std::printf("perinom: %s: estimate per rank up to %.1f MiB (rank %d); %.1f MiB on the busiest host (%.0f ranks, "
              "%.0f MiB available)\n",
              s.name.c_str(), mib(m.most_bytes), most, mib(m.host_bytes), host_ranks[busiest], mib(host_room[busiest]));
  std::fflush(stdout);
  const std::string key = local_bonds > 500.0 * local_particles ? "discretization.horizon.ratio" : "discretization.dx";
  const std::string cure = key == "discretization.dx" ? "; use a larger dx or more hosts" : "; use a smaller horizon or more hosts";
  std::ostringstream what;
  if (max_memory > 0.0 && m.most_bytes > max_memory) {
    char allowed[32];  // (100K read "0 MiB")
    std::snprintf(allowed, sizeof allowed, "%.3g", mib(max_memory));
    what << key << ": rank " << most << " needs about " << long(mib(m.most_bytes)) << " MiB, more than the "
         << allowed << " MiB allowed to each rank by --max-memory" << cure;
    throw InputErrorOnEveryRank(what.str());  // every rank holds every row
  }
  for (const auto& [host, need] : host_need)
    if (max_memory <= 0.0 && host_room[host] > 0.0 && need > host_room[host]) {
      what << key << ": the " << long(host_ranks[host]) << " ranks of one host need about " << long(mib(need))
           << " MiB, more than the " << long(mib(host_room[host])) << " MiB it has available" << cure
           << " (--max-memory, a bound per rank, overrides the check)";
      throw InputErrorOnEveryRank(what.str());  // every rank holds every row
    }
  return m;
}

}  // namespace perinom::cli

// The memory a run may take includes a container's or a batch job's cgroup limit, which
// MemAvailable (the host's) does not show: cgroup_room read on a made-up cgroup tree, in
// both versions, with the limit on the process's own cgroup or an ancestor, and the
// reclaimable (inactive) page cache not counted as used.
#include <catch2/catch.hpp>

#include <fstream>

#include "../support/cli.hpp"
#include "perinom/core/memory.hpp"

using namespace perinom;

namespace {

void write(const cli_test::fs::path& file, const std::string& text) {
  cli_test::fs::create_directories(file.parent_path());
  std::ofstream(file) << text << "\n";
}

}  // namespace

TEST_CASE("the room a memory cgroup leaves: version 2, the least over the cgroup and its ancestors", "[core]") {
  cli_test::ScratchDir d;
  const auto root = d.path / "sys";
  write(d.path / "cgroup", "0::/job/step");
  write(root / "job/step/memory.max", "max");  // the step sets none
  write(root / "job/step/memory.current", "100");
  write(root / "job/memory.max", "1000");
  write(root / "job/memory.current", "400");
  CHECK(cgroup_room((d.path / "cgroup").string(), root.string()) == 600.0);
  write(root / "job/step/memory.max", "300");  // now the step is the tighter one
  CHECK(cgroup_room((d.path / "cgroup").string(), root.string()) == 200.0);
  // Inactive page cache is reclaimable: not counted as used.
  write(root / "job/step/memory.stat", "anon 60\nfile 40\ninactive_file 30\nactive_file 10");
  CHECK(cgroup_room((d.path / "cgroup").string(), root.string()) == 230.0);
  write(root / "job/memory.max", "max");
  write(root / "job/step/memory.max", "max");
  CHECK(cgroup_room((d.path / "cgroup").string(), root.string()) == -1.0);  // no limit anywhere
  CHECK(cgroup_room((d.path / "absent").string(), root.string()) == -1.0);
}

TEST_CASE("the room a memory cgroup leaves: version 1's memory controller, its no-limit number", "[core]") {
  cli_test::ScratchDir d;
  const auto root = d.path / "sys";
  write(d.path / "cgroup", "12:cpu,cpuacct:/slurm/job_7\n4:memory:/slurm/job_7/step_0\n1:name=systemd:/x");
  write(root / "memory/slurm/job_7/step_0/memory.limit_in_bytes", "9223372036854771712");  // no limit
  write(root / "memory/slurm/job_7/step_0/memory.usage_in_bytes", "50");
  write(root / "memory/slurm/job_7/memory.limit_in_bytes", "8000");
  write(root / "memory/slurm/job_7/memory.usage_in_bytes", "3000");
  CHECK(cgroup_room((d.path / "cgroup").string(), root.string()) == 5000.0);
  write(root / "memory/slurm/job_7/memory.stat", "cache 2500\ninactive_file 9\ntotal_inactive_file 2000");
  CHECK(cgroup_room((d.path / "cgroup").string(), root.string()) == 7000.0);
  // Usage above the limit (less the cache) leaves nothing, not a negative room.
  write(root / "memory/slurm/job_7/memory.usage_in_bytes", "11000");
  CHECK(cgroup_room((d.path / "cgroup").string(), root.string()) == 0.0);
}

TEST_CASE("the memory available is positive here and no more than MemAvailable", "[core]") {
  const double available = available_memory();
  CHECK(available > 0.0);
  std::ifstream in("/proc/meminfo");
  double mem_available = 0.0;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("MemAvailable:", 0) == 0) mem_available = 1024.0 * std::atof(line.c_str() + 13);
  REQUIRE(mem_available > 0.0);
  // (MemAvailable moves between the two reads: a margin of 64 MiB.)
  CHECK(available <= mem_available + 64.0 * 1048576.0);
}

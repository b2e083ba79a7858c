#pragma once
/// @file What memory this process has and may take, from /proc (Linux): the pre-run estimate
/// of the command line and Newton's check before it factors a Jacobian compare against it.

#include <string>

namespace perinom {

/// The memory a run may take: MemAvailable of /proc/meminfo, bounded by the address-space
/// limit (ulimit -v) less what the process has mapped and by the room its memory cgroups
/// leave (cgroup_room). 0 when unknown.
double available_memory();

/// The least room (limit less usage, bytes) that the memory cgroups listed in `cgroup_file`
/// (the format of /proc/self/cgroup) and their ancestors leave under `root`: version 2's
/// memory.max and memory.current, version 1's memory.limit_in_bytes and
/// memory.usage_in_bytes under root/memory; the usage less the inactive file cache of
/// memory.stat (inactive_file, v1 total_inactive_file), which is reclaimed before an OOM. -1 when none sets a limit (or none is found).
/// A container or a batch job (Slurm confines a job to its cgroup) is limited here, not in
/// MemAvailable, which is the host's.
double cgroup_room(const std::string& cgroup_file = "/proc/self/cgroup", const std::string& root = "/sys/fs/cgroup");

/// This process's peak resident size so far (VmHWM of /proc/self/status), in bytes; 0 if unknown.
double peak_resident_bytes();

/// This process's resident size now (VmRSS of /proc/self/status), in bytes; 0 if unknown.
double resident_bytes();

}  // namespace perinom

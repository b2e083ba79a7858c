#pragma once
/// @file What memory this process has and may take, from /proc (Linux): the pre-run estimate
/// of the command line and Newton's check before it factors a Jacobian compare against it.

namespace perinom {

/// The memory a run may take: MemAvailable of /proc/meminfo, bounded by the address-space
/// limit (ulimit -v) less what the process has mapped. 0 when unknown.
double available_memory();

/// This process's peak resident size so far (VmHWM of /proc/self/status), in bytes; 0 if unknown.
double peak_resident_bytes();

/// This process's resident size now (VmRSS of /proc/self/status), in bytes; 0 if unknown.
double resident_bytes();

}  // namespace perinom

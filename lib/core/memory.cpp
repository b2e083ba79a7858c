#include "perinom/core/memory.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>

namespace perinom {
namespace {

/// A field of a /proc file in kB ("VmHWM:", "MemAvailable:"), in bytes; 0 if absent.
double proc_kib(const char* file, const std::string& field) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(field, 0) == 0) return 1024.0 * std::atof(line.c_str() + field.size());
  return 0.0;
}

}  // namespace

double available_memory() {
  double available = proc_kib("/proc/meminfo", "MemAvailable:");
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
    const double room = double(as.rlim_cur) - proc_kib("/proc/self/status", "VmSize:");
    available = available > 0.0 ? std::min(available, room) : room;
  }
  return std::max(available, 0.0);
}

double peak_resident_bytes() { return proc_kib("/proc/self/status", "VmHWM:"); }

double resident_bytes() { return proc_kib("/proc/self/status", "VmRSS:"); }

}  // namespace perinom

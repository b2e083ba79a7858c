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

/// The number a cgroup file holds; -1 when it is absent or says "max" (no limit). Version 1
/// writes "no limit" as a number near 2^63.
double cgroup_number(const std::string& file) {
  std::ifstream in(file);
  std::string word;
  if (!(in >> word) || word == "max") return -1.0;
  const double x = std::atof(word.c_str());
  return x > 0x1p60 ? -1.0 : x;
}

/// A "key value" line's value (bytes) in a cgroup's memory.stat; 0 if absent.
double stat_bytes(const std::string& file, const std::string& key) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + " ", 0) == 0) return std::atof(line.c_str() + key.size() + 1);
  return 0.0;
}

/// limit - usage of one cgroup folder, or -1 without a limit there. The usage counts the
/// page cache too; its inactive file pages (`cache_key` in memory.stat) are reclaimed before
/// the cgroup's OOM killer acts, so they are not taken as used (the working set that
/// container tools report): a job that has written gigabytes of output is not refused for it.
double folder_room(const std::string& folder, const char* limit_file, const char* usage_file, const char* cache_key) {
  const double limit = cgroup_number(folder + "/" + limit_file);
  if (limit < 0.0) return -1.0;
  const double usage = std::max(cgroup_number(folder + "/" + usage_file), 0.0);
  const double cache = stat_bytes(folder + "/memory.stat", cache_key);
  return std::max(limit - std::max(usage - cache, 0.0), 0.0);
}

}  // namespace

double cgroup_room(const std::string& cgroup_file, const std::string& root) {
  double room = -1.0;
  auto least = [&](double r) {
    if (r >= 0.0) room = room < 0.0 ? r : std::min(room, r);
  };
  std::ifstream in(cgroup_file);
  for (std::string line; std::getline(in, line);) {
    // "0::/path" (version 2) or "N:memory:/path" (version 1, among other controllers).
    const auto a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1);
    const bool v2 = line.compare(0, a, "0") == 0 && controllers.empty();
    if (!v2 && controllers.find("memory") == std::string::npos) continue;
    std::string path = line.substr(b + 1);
    const std::string base = v2 ? root : root + "/memory";
    // The limit may sit on any ancestor (a batch job's, its step's): the least room of all.
    for (;;) {
      const std::string folder = base + (path == "/" ? "" : path);
      least(v2 ? folder_room(folder, "memory.max", "memory.current", "inactive_file")
               : folder_room(folder, "memory.limit_in_bytes", "memory.usage_in_bytes", "total_inactive_file"));
      if (path.empty() || path == "/") break;
      const auto slash = path.rfind('/');
      path = slash == 0 || slash == std::string::npos ? "/" : path.substr(0, slash);
    }
  }
  return room;
}

double available_memory() {
  double available = proc_kib("/proc/meminfo", "MemAvailable:");
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
    const double room = double(as.rlim_cur) - proc_kib("/proc/self/status", "VmSize:");
    available = available > 0.0 ? std::min(available, room) : room;
  }
  // A container's or a batch job's memory limit, which MemAvailable (the host's) does not see.
  const double cgroup = cgroup_room();
  if (cgroup >= 0.0) available = available > 0.0 ? std::min(available, cgroup) : cgroup;
  return std::max(available, 0.0);
}

double peak_resident_bytes() { return proc_kib("/proc/self/status", "VmHWM:"); }

double resident_bytes() { return proc_kib("/proc/self/status", "VmRSS:"); }

}  // namespace perinom

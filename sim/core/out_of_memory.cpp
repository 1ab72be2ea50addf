#include "sim/core/out_of_memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace spume {
namespace {

std::atomic<uint64_t> g_last_failed{0};

// A "Key:   123 kB" line of a /proc file, in bytes; 0 when absent.
uint64_t proc_kib_field(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key + ":", 0) == 0) return uint64_t(std::strtoull(line.c_str() + key.size() + 1, nullptr, 10)) << 10;
  return 0;
}

}  // namespace

std::string memory_situation() {
  const uint64_t address_space = proc_kib_field("/proc/self/status", "VmSize");
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    return str("; the process had ", byte_size_text(address_space), " of address space, its limit (ulimit -v) is ",
               byte_size_text(uint64_t(limit.rlim_cur)));
  const uint64_t resident = proc_kib_field("/proc/self/status", "VmRSS");
  const uint64_t available = proc_kib_field("/proc/meminfo", "MemAvailable");
  if (resident == 0 && available == 0) return "";
  return str("; the process held ", byte_size_text(resident), " and the system had ", byte_size_text(available),
             " available");
}

void record_failed_allocation(uint64_t bytes) { g_last_failed.store(bytes, std::memory_order_relaxed); }

std::string byte_size_text(uint64_t bytes) {
  const char* units[] = {"KiB", "MiB", "GiB", "TiB"};
  if (bytes < 1024) return str(bytes, bytes == 1 ? " byte" : " bytes");
  double value = double(bytes) / 1024.0;
  int unit = 0;
  while (value >= 1024.0 && unit < 3) value /= 1024.0, ++unit;
  char text[32];
  std::snprintf(text, sizeof text, value < 10.0 ? "%.1f %s" : "%.0f %s", value, units[unit]);
  return text;
}

std::string out_of_memory_message(std::string_view what, uint64_t bytes) {
  const uint64_t failed = g_last_failed.exchange(0, std::memory_order_relaxed);
  std::string message = "out of memory";
  if (!what.empty()) message += str(" ", what);
  if (bytes > 0) message += str(" (", byte_size_text(bytes), ")");
  else if (failed > 0) message += str(" (an allocation of ", byte_size_text(failed), " failed)");
  return message + memory_situation();
}

}  // namespace spume

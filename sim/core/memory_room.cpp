#include "sim/core/memory_room.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <utility>

#include "sim/core/error.h"
#include "sim/core/out_of_memory.h"

namespace spume {
namespace {

// A number from a one-number file (cgroup v2's memory.max holds "max" when unlimited).
std::optional<double> number_in(const char* path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text)) return std::nullopt;
  try {
    size_t used = 0;
    const double value = std::stod(text, &used);
    if (used != text.size()) return std::nullopt;
    return value;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// A "key value" line's value from a cgroup's memory.stat.
std::optional<double> stat_value(const std::string& path, const std::string& wanted) {
  std::ifstream in(path);
  std::string key;
  double value = 0.0;
  while (in >> key >> value)
    if (key == wanted) return value;
  return std::nullopt;
}

// This process's cgroup path under the hierarchy /proc/self/cgroup names (v2: "0::/path"; v1 memory
// controller: "N:memory:/path"), "" when not found.
std::string cgroup_path(bool v2) {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line)) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    if (v2 ? line.compare(0, first, "0") == 0 && controllers.empty() : controllers == "memory")
      return line.substr(second + 1);
  }
  return "";
}

// Room left under the memory limit of this process's cgroup (v2 memory.max, or v1's
// memory.limit_in_bytes): the limit less what is charged, the page cache the kernel can drop
// (inactive files) not counted. Looked up at the process's own group, then at the mount's root (a
// container sees its group there). nullopt without a limit.
std::optional<double> cgroup_room() {
  struct Layout {
    bool v2;
    std::string root, limit, usage, inactive;
  };
  const Layout layouts[] = {{true, "/sys/fs/cgroup", "memory.max", "memory.current", "inactive_file"},
                            {false, "/sys/fs/cgroup/memory", "memory.limit_in_bytes", "memory.usage_in_bytes",
                             "total_inactive_file"}};
  for (const Layout& l : layouts)
    for (const std::string& dir : {l.root + cgroup_path(l.v2), l.root}) {
      const std::optional<double> limit = number_in((dir + "/" + l.limit).c_str());
      const std::optional<double> usage = number_in((dir + "/" + l.usage).c_str());
      if (!limit || !usage || *limit >= 0x1p60) continue;  // v1 writes "no limit" as about 2^63
      const double droppable = stat_value(dir + "/memory.stat", l.inactive).value_or(0.0);
      return std::max(0.0, *limit - std::max(0.0, *usage - droppable));
    }
  return std::nullopt;
}

std::string millions(uint64_t n) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, n >= 100000 ? "%.1fM" : "%.0f", n >= 100000 ? double(n) / 1e6 : double(n));
  return buffer;
}

}  // namespace

std::optional<double> available_memory_bytes() {
  std::optional<double> available;
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  double kilobytes = 0.0;
  while (meminfo >> key >> kilobytes >> unit)
    if (key == "MemAvailable:") available = kilobytes * 1024.0;
  if (const std::optional<double> room = cgroup_room()) available = available ? std::min(*available, *room) : *room;
  return available;
}

MemoryRoom::MemoryRoom(std::string what, std::string items, double bytes_per_item, std::string remedy,
                       Available available)
    : what_(std::move(what)),
      items_(std::move(items)),
      remedy_(std::move(remedy)),
      bytes_per_item_(bytes_per_item),
      available_(std::move(available)) {}

void MemoryRoom::check(uint64_t count, const std::string& where) {
  std::lock_guard lock(mutex_);
  const double needed = double(count) * bytes_per_item_, more = needed - held_;
  if (more <= 0.0) return;  // within what is held: nothing to ask
  const std::optional<double> available = available_();
  if (available && more > *available)
    fail(where, where.empty() ? "" : ": ", what_, " cannot hold ", millions(count), " ", items_, ": at about ",
         bytes_per_item_, " bytes each they need ", byte_size_text(uint64_t(needed)), ", ",
         byte_size_text(uint64_t(more)), " more than it holds, and ", byte_size_text(uint64_t(*available)),
         " is available (MemAvailable, or the cgroup's limit); ", remedy_);
  held_ = needed;
}

void MemoryRoom::holding(double bytes) {
  std::lock_guard lock(mutex_);
  held_ = std::max(held_, bytes);
}

}  // namespace spume

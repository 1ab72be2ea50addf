#pragma once
// Room for a working set that grows with a particle count, checked before it grows, so that a frame
// that cannot fit is refused with the numbers instead of being killed by the kernel's out-of-memory
// killer (Linux overcommits: a large allocation succeeds and the process dies when it touches it).
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

namespace spume {

// The memory the kernel could give this process now: /proc/meminfo's MemAvailable (free memory and
// reclaimable caches), lowered to the room left under the process's cgroup limit (v2 or v1) when there
// is one. nullopt where neither can be read.
std::optional<double> available_memory_bytes();

// Refuses a count whose growth beyond what the stage holds (the working set of the largest count that
// passed, at `bytes_per_item`, measured over the whole process, or what it was told it holds) needs
// more than is available. Thread-safe (a render checks the frame it prefetches).
class MemoryRoom {
 public:
  using Available = std::function<std::optional<double>()>;
  // what: "the diffuse stage"; items: "diffuse particles"; remedy: what the user can change.
  MemoryRoom(std::string what, std::string items, double bytes_per_item, std::string remedy,
             Available available = available_memory_bytes);
  // Throws Error naming `where` (e.g. a file; "": the caller's context names it) when `count` cannot
  // fit.
  void check(uint64_t count, const std::string& where);
  // The stage holds at least `bytes` already, outside what check() has seen (e.g. a restart's particles).
  void holding(double bytes);

 private:
  std::mutex mutex_;
  std::string what_, items_, remedy_;
  double bytes_per_item_;
  Available available_;
  double held_ = 0.0;  // bytes: the largest count that passed at bytes_per_item_, or what holding() said
};

}  // namespace spume

#pragma once
// One writer per output folder (OUT/<scene>/). A simulation holds the folder alone; renders share it
// with renders of the same render keys (the tasks of a farm array, which draw disjoint frames alike)
// and wait for a simulation or for renders with other keys to finish. A second run therefore never
// mixes its frames or caches into another's; it says whom it waits for, and goes on when they are done.
//
// flock(2) on OUT/<scene>/.lock, with `.lock.gate` taken briefly around every change so that the
// holders' keys (kept in `.lock.keys`) and the lock always agree. Locks die with their process: a
// killed run never leaves the folder locked. (flock is not reliable on every network file system;
// farms across machines share frames, never caches, and render frames whose records match.)
#include <filesystem>
#include <functional>
#include <string>

namespace spume {

// Runs `update` holding the folder's gate (briefly, never across a frame): for a small file that runs
// sharing the folder each rewrite in turn, e.g. the render's per-frame timings.
void update_under_gate(const std::filesystem::path& dir, const std::function<void()>& update);

class OutputLock {
 public:
  // Exclusive: a simulation. Shared: a render, sharing with holders of the same `keys` only.
  enum class Mode { Exclusive, Shared };
  // Blocks until granted; prints once to stderr whom it waits for, unless quiet. `what` names this
  // run in others' messages (e.g. "spume simulate").
  OutputLock(const std::filesystem::path& dir, Mode mode, const std::string& keys, const std::string& what, bool quiet);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace spume

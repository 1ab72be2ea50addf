#include "sim/core/thread_budget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "sim/core/parallel.h"

namespace spume {

int limit_threads_to_address_space() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
  uint64_t pages = 0;
  std::ifstream("/proc/self/statm") >> pages;
  const uint64_t used = pages * uint64_t(sysconf(_SC_PAGESIZE));
  const uint64_t room = uint64_t(limit.rlim_cur) > used ? uint64_t(limit.rlim_cur) - used : 0;
  // Worker stacks may take a quarter of the room; the rest is for the work. The calling thread has its
  // stack already.
  const uint64_t stack = tbb::global_control::active_value(tbb::global_control::thread_stack_size);
  const int fit = 1 + int(room / 4 / (stack > 0 ? stack : uint64_t(4) << 20));
  if (fit >= tbb::info::default_concurrency()) return 0;
  set_thread_count(fit);
  return fit;
}

}  // namespace spume

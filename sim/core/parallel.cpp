#include "sim/core/parallel.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <utility>

namespace spume {
namespace {
// Never destroyed: at exit, lifting the limit would have the pool start the workers it was kept from,
// which throws from a destructor (and aborts) when they cannot start (a small address space).
tbb::global_control* g_limit = nullptr;
int g_threads = 0;
}  // namespace

void set_thread_count(int threads) {
  g_threads = threads > 0 ? threads : tbb::info::default_concurrency();
  auto* limit = new tbb::global_control(tbb::global_control::max_allowed_parallelism, size_t(g_threads));
  delete std::exchange(g_limit, limit);
}

int thread_count() { return g_threads > 0 ? g_threads : tbb::info::default_concurrency(); }

}  // namespace spume

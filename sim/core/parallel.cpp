#include "sim/core/parallel.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

namespace spume {
namespace {
std::unique_ptr<tbb::global_control> g_limit;
int g_threads = 0;
}  // namespace

void set_thread_count(int threads) {
  g_threads = threads > 0 ? threads : tbb::info::default_concurrency();
  g_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(g_threads));
}

int thread_count() { return g_threads > 0 ? g_threads : tbb::info::default_concurrency(); }

}  // namespace spume

#include "sim/core/huge_pages.h"

#include <atomic>

namespace spume {
namespace {

std::atomic<int> g_open_scopes{0};

}  // namespace

HugePagesForLargeBlocks::HugePagesForLargeBlocks() { g_open_scopes.fetch_add(1, std::memory_order_relaxed); }

HugePagesForLargeBlocks::~HugePagesForLargeBlocks() { g_open_scopes.fetch_sub(1, std::memory_order_relaxed); }

bool HugePagesForLargeBlocks::active() { return g_open_scopes.load(std::memory_order_relaxed) > 0; }

}  // namespace spume

#include "sim/core/allocation_budget.h"

#include <cstdlib>
#include <new>

#include "sim/core/huge_pages.h"
#include "sim/core/out_of_memory.h"

namespace spume {
namespace {

thread_local AllocationBudget* t_budget = nullptr;

}  // namespace

AllocationBudget::AllocationBudget(size_t bytes) : bytes_(bytes), left_(bytes), outer_(t_budget) { t_budget = this; }

AllocationBudget::~AllocationBudget() { t_budget = outer_; }

bool AllocationBudget::take(size_t n) {
  AllocationBudget* budget = t_budget;
  if (!budget) return true;
  if (n > budget->left_) {
    budget->exceeded_ = true;
    return false;
  }
  budget->left_ -= n;
  return true;
}

}  // namespace spume

// The replaceable allocation functions (the array and nothrow forms of libstdc++ call this one). Memory
// comes from malloc, as libstdc++'s own operator new takes it, so its operator delete frees it. Large
// blocks are advised huge pages while a stage asks for it (sim/core/huge_pages.h).
void* operator new(std::size_t n) {
  if (!spume::AllocationBudget::take(n)) throw std::bad_alloc();
  for (;;) {
    if (void* p = std::malloc(n ? n : 1)) {
      if (n >= spume::kHugePageRequestBytes && spume::HugePagesForLargeBlocks::active()) spume::advise_huge_pages(p, n);
      return p;
    }
    std::new_handler handler = std::get_new_handler();
    if (!handler) {
      spume::record_failed_allocation(n);  // so the message can say how much was asked for
      throw std::bad_alloc();
    }
    handler();
  }
}

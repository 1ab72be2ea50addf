#include "sim/core/allocation_budget.h"

#include <cstdlib>
#include <new>

#include "sim/core/huge_pages.h"

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
// blocks (a frame's columns: std::vector's, which every stage fills right away) are advised huge pages
// first: on a virtual machine their page faults were a sixth of a 15M diffuse frame's time.
void* operator new(std::size_t n) {
  if (!spume::AllocationBudget::take(n)) throw std::bad_alloc();
  for (;;) {
    if (void* p = std::malloc(n ? n : 1)) {
      if (n >= spume::kHugePageRequestBytes) spume::advise_huge_pages(p, n);
      return p;
    }
    std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

#include "sim/core/allocation_budget.h"


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

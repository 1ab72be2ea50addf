#pragma once
// A bound on what a library may allocate while it parses an untrusted file on this thread. OpenVDB
// reads a length from the file and allocates it before reading the bytes, so a damaged length field
// (a flipped bit in a metadata string's size) makes it allocate and clear gigabytes, entry after
// entry: the read hangs for minutes instead of failing. While an AllocationBudget lives, every
// operator new on its thread counts against it, and one that would pass it throws std::bad_alloc,
// which the library unwinds like any failed allocation. Other threads are not counted. Only the
// spume command counts: its operator new (render/app/process_hooks.cpp) asks take(); a library
// replaces no allocation function, so elsewhere (tests, fuzzers) the budget is never consulted.
#include <cstddef>

namespace spume {

class AllocationBudget {
 public:
  explicit AllocationBudget(size_t bytes);
  ~AllocationBudget();
  AllocationBudget(const AllocationBudget&) = delete;
  AllocationBudget& operator=(const AllocationBudget&) = delete;

  // True when an allocation was refused for passing the budget.
  bool exceeded() const { return exceeded_; }
  size_t bytes() const { return bytes_; }

  // For the spume command's operator new: counts `n` bytes against the thread's budget, if any;
  // false when it would pass it.
  static bool take(size_t n);

 private:
  size_t bytes_, left_;
  bool exceeded_ = false;
  AllocationBudget* outer_;
};

}  // namespace spume

#pragma once
// Under an address-space limit (ulimit -v) every worker thread's stack takes address space as well, and
// a pool thread that cannot start aborts the process from inside the pool. So the pool is sized to what
// the limit leaves room for, down to the calling thread alone; without a limit nothing changes.
namespace spume {

// Call once, before any parallel work. Returns the threads the pool was limited to, 0 when unchanged
// (--threads may set another count later: the user's choice).
int limit_threads_to_address_space();

}  // namespace spume

#include "render/app/process_hooks.h"

#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <new>

#include "sim/core/allocation_budget.h"
#include "sim/core/huge_pages.h"
#include "sim/core/out_of_memory.h"
#include "sim/io/library_abort_guard.h"

namespace spume {
namespace {

struct sigaction g_previous_abort {};

void write_all(const char* text) {
  size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n, left -= size_t(n);
  }
}

// Only async-signal-safe calls: write, _exit, sigaction, raise. An abort outside a guard goes to the
// handler that was there before (a debugger's, a sanitizer's), or takes the default action.
void on_abort(int signal) {
  if (const char* message = library_abort_message()) {
    write_all("spume: error: ");
    write_all(message);
    write_all("\n");
    ::_exit(1);
  }
  sigaction(SIGABRT, &g_previous_abort, nullptr);
  std::raise(signal);
}

}  // namespace

void install_process_hooks() {
  struct sigaction action {};
  action.sa_handler = on_abort;
  sigemptyset(&action.sa_mask);
  sigaction(SIGABRT, &action, &g_previous_abort);
}

}  // namespace spume

// The replaceable allocation function (the array and nothrow forms of libstdc++ call this one): while an
// AllocationBudget lives on the thread, allocations count against it; while a stage asks for it
// (HugePagesForLargeBlocks), large blocks are advised huge pages. Memory comes from malloc, as
// libstdc++'s operator new takes it, so its operator delete frees it.
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

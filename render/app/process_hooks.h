#pragma once
// What the spume command installs for its whole process, and no library does: a replacement operator
// new (an allocation budget for reading untrusted files, sim/core/allocation_budget.h, and huge-page
// advice for large blocks, sim/core/huge_pages.h), defined in process_hooks.cpp, and a SIGABRT handler
// that turns an abort inside a LibraryAbortGuard into exit 1 with its message
// (sim/io/library_abort_guard.h), chaining to the handler before it otherwise.
namespace spume {

// Installs the SIGABRT handler; main calls it first. (The operator new needs no call: linking it in
// replaces the C++ library's.)
void install_process_hooks();

}  // namespace spume

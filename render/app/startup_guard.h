#pragma once
// While the shared libraries load, before main, log4cplus (which OpenVDB links) starts a pool of threads
// in its initialiser. Under an address-space limit (ulimit -v) too small for their stacks, the exception
// that reports it would abort the process before main could say anything. From the executable's
// .preinit_array, which runs before any library's initialiser, until main calls end_startup_guard(), a
// terminate handler says what failed and what the address space was, and exits with status 1.
namespace spume {

// Restores the terminate handler the process had (main calls it first): later failures are not this.
void end_startup_guard();

}  // namespace spume

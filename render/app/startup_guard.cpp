#include "render/app/startup_guard.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

namespace spume {
namespace {

std::terminate_handler g_previous = nullptr;

// The process's address space in MiB, from /proc/self/statm (its first field, in pages); 0 if unknown.
// Plain system calls: memory is what ran out.
long address_space_mib() {
  const int fd = open("/proc/self/statm", O_RDONLY);
  if (fd < 0) return 0;
  char text[64] = {};
  const ssize_t n = read(fd, text, sizeof text - 1);
  close(fd);
  if (n <= 0) return 0;
  return std::strtol(text, nullptr, 10) * sysconf(_SC_PAGESIZE) / (1024 * 1024);
}

[[noreturn]] void startup_failed() {
  const char* what = "an exception";
  try {
    if (const std::exception_ptr e = std::current_exception()) std::rethrow_exception(e);
  } catch (const std::exception& e) {
    what = e.what();
  } catch (...) {
  }
  char text[512];
  rlimit limit{};
  const bool limited = getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY;
  const int length =
      limited ? std::snprintf(text, sizeof text,
                              "spume: error: cannot start: a library failed while loading, before spume could run "
                              "(%s): %ld MiB of address space were in use, and its limit (ulimit -v) of %ld MiB "
                              "leaves no room for the threads the libraries start; allow more (ulimit -v 1048576 "
                              "allows 1 GiB)\n",
                              what, address_space_mib(), long(limit.rlim_cur / (1024 * 1024)))
              : std::snprintf(text, sizeof text,
                              "spume: error: cannot start: a library failed while loading, before spume could run "
                              "(%s)\n",
                              what);
  if (length > 0) {
    const ssize_t written = write(STDERR_FILENO, text, size_t(length));
    (void)written;  // nothing is left to report a failed write to
  }
  _exit(1);
}

void begin_startup_guard(int, char**, char**) { g_previous = std::set_terminate(startup_failed); }

}  // namespace

void end_startup_guard() { std::set_terminate(g_previous); }

}  // namespace spume

// Runs before the shared libraries' initialisers (only an executable's .preinit_array does).
__attribute__((section(".preinit_array"), used)) static void (*const spume_startup_guard)(int, char**, char**) =
    spume::begin_startup_guard;

#include "sim/io/library_abort_guard.h"

#include <csignal>
#include <cstring>
#include <mutex>

#include <unistd.h>

namespace spume {
namespace {

thread_local const char* t_message = nullptr;

void write_all(const char* text) {
  size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n, left -= size_t(n);
  }
}

// Only async-signal-safe calls: write, _exit, signal, raise.
void on_abort(int signal) {
  if (const char* message = t_message) {
    write_all("spume: error: ");
    write_all(message);
    write_all("\n");
    ::_exit(1);
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

LibraryAbortGuard::LibraryAbortGuard(const std::string& message) : outer_(t_message), message_(message) {
  static std::once_flag once;
  std::call_once(once, [] {
    struct sigaction action {};
    action.sa_handler = on_abort;
    sigemptyset(&action.sa_mask);
    sigaction(SIGABRT, &action, nullptr);
  });
  t_message = message_.c_str();
}

LibraryAbortGuard::~LibraryAbortGuard() { t_message = outer_; }

}  // namespace spume

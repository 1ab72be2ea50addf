#pragma once
// Debian's OpenVDB keeps its assertions: a damaged file can make it call abort() (a compressed page
// whose header says it holds 0 bytes, found by mutating a real Mantaflow frame), which would end spume
// with a core dump and no word about the file. While a LibraryAbortGuard lives on a thread, that
// thread's abort has a message: the spume command's SIGABRT handler (render/app/process_hooks.cpp)
// prints "spume: error: FILE: WHAT" and exits 1 (no output is ever half written: outputs are renamed
// into place). The library installs no handler: without the command's (tests, fuzzers) an abort aborts.
#include <string>

namespace spume {

class LibraryAbortGuard {
 public:
  // `message`: what to say, e.g. "f.vdb: OpenVDB stopped on a check while reading this file (damaged?)".
  explicit LibraryAbortGuard(const std::string& message);
  ~LibraryAbortGuard();
  LibraryAbortGuard(const LibraryAbortGuard&) = delete;
  LibraryAbortGuard& operator=(const LibraryAbortGuard&) = delete;

 private:
  const char* outer_;
  std::string message_;
};

// The message of the guard living on the calling thread, or nullptr. Async-signal-safe (a
// thread-local read), for a SIGABRT handler.
const char* library_abort_message();

}  // namespace spume

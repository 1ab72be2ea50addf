#pragma once
// Runs a shell command line from a test (a browser, bash -n, a child program): its exit status and
// what it wrote to stdout. The spume binary itself: run_spume (tests/support/run_spume.h).
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace spume::testing {

struct CommandResult {
  int status = -1;     // the exit status; -1 when the program did not exit normally (a signal)
  std::string output;  // stdout, and stderr too unless it was asked for apart
  std::string err;     // stderr, when asked for apart (SpumeOptions::separate_stderr)
};

// `command` through /bin/sh; output holds what it wrote to stdout (redirect stderr in the command to
// capture it as well).
inline CommandResult run_command(const std::string& command) {
  CommandResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer;
  while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace spume::testing

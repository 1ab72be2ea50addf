#pragma once
// Runs a shell command for the tests of the spume binary: its exit status (-1 when it did not exit
// normally) and what it wrote to stdout (redirect stderr in the command to capture it as well).
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace spume {

struct CommandResult {
  int status = -1;
  std::string output;
};

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

}  // namespace spume

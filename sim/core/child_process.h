#pragma once
// Runs a program (found on PATH or by path) with its stdout and stderr captured, and waits for it.
#include <string>
#include <vector>

namespace spume {

struct ProcessResult {
  bool started = false;   // false: the program could not be run (not found, not executable)
  int exit_code = -1;     // -1 when killed by a signal
  int signal = 0;         // the signal that ended it, or 0
  std::string output;     // stdout and stderr, interleaved
  std::string start_error;
};

// `environment`: "NAME=value" entries added to (or replacing) the ones this process has.
ProcessResult run_process(const std::vector<std::string>& argv, const std::vector<std::string>& environment = {});

}  // namespace spume

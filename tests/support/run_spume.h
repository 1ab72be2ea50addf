#pragma once
// Runs the spume binary under test (SPUME_BINARY, set by tests/CMakeLists.txt for each test binary that
// starts it) and returns its exit status and output.
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

#include "sim/core/sanitizers.h"
#include "tests/support/run_command.h"

namespace spume::testing {

struct SpumeOptions {
  bool separate_stderr = false;  // stderr into `err` (through a file), stdout alone into `output`
  std::string environment;       // assignments put before the binary, e.g. "PATH=/nonexistent"
  std::string before;            // shell commands run first in the same shell, e.g. "ulimit -v 1572864"

  // Named starting points (designated initialisers that skip members warn under -Wextra).
  // stderr captured apart from stdout, with `environment` assignments put before the binary.
  static SpumeOptions stderr_apart(std::string environment = "") {
    SpumeOptions options;
    options.separate_stderr = true;
    options.environment = std::move(environment);
    return options;
  }
  // Only `shell_commands` run first.
  static SpumeOptions after(std::string shell_commands) {
    SpumeOptions options;
    options.before = std::move(shell_commands);
    return options;
  }
};

// `spume ARGUMENTS` (shell words: quote patterns such as 'cache/f_%d.bgeo'). By default stdout and
// stderr are captured together in the order written, as a terminal shows them.
// Under AddressSanitizer (the SPUME_SANITIZE build), which reserves terabytes of address space as a
// process starts, a `ulimit -v` in `before` is left out: what such a test checks of the messages still
// holds; a test whose point is the limit itself skips (SPUME_SKIP_UNDER_ADDRESS_SANITIZER).
inline CommandResult run_spume(const std::string& arguments, const SpumeOptions& options = {}) {
  std::string command;
  if (!options.before.empty() && !(kAddressSanitizer && options.before.starts_with("ulimit -v")))
    command += options.before + "; ";
  if (!options.environment.empty()) command += options.environment + " ";
  command += std::string(SPUME_BINARY) + " " + arguments;
  if (!options.separate_stderr) return run_command(command + " 2>&1");
  static std::atomic<int> counter = 0;
  const std::filesystem::path err_file = std::filesystem::temp_directory_path() /
                                         ("spume_stderr_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  CommandResult r = run_command(command + " 2>'" + err_file.string() + "'");
  std::ifstream in(err_file, std::ios::binary);
  r.err.assign(std::istreambuf_iterator<char>(in), {});
  std::filesystem::remove(err_file);
  return r;
}

}  // namespace spume::testing

// For a test of what spume does under an address-space limit, which a process running AddressSanitizer
// cannot be started under.
#define SPUME_SKIP_UNDER_ADDRESS_SANITIZER()                                                       \
  if (::spume::kAddressSanitizer)                                                                 \
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no process of this build " \
                  "starts under ulimit -v"

#include "sim/io/contained_read.h"

#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <set>
#include <vector>

#include "sim/core/child_process.h"
#include "sim/core/error.h"
#include "sim/core/sanitizers.h"

namespace spume {
namespace {

std::mutex g_mutex;
std::filesystem::path g_helper;       // empty: reads are not contained
std::set<std::string> g_read_cleanly; // the file versions a child has read cleanly
uint64_t g_budget_in_force = 0;

// What identifies one version of a file for one reader: a file rewritten in place gets another.
std::string version_key(const std::filesystem::path& path, const std::string& format, const std::string& grid) {
  std::error_code size_error, time_error, path_error;
  const uintmax_t size = std::filesystem::file_size(path, size_error);
  const auto time = std::filesystem::last_write_time(path, time_error);
  const std::filesystem::path absolute = std::filesystem::absolute(path, path_error);
  return str(path_error ? path.string() : absolute.string(), '\n', size_error ? 0 : size, '\n',
             time_error ? 0 : time.time_since_epoch().count(), '\n', format, '\n', grid);
}

std::string library_of(const std::string& format) { return format == "vdb" ? "OpenVDB" : format; }

// The last line of `output` that is not blank.
std::string last_line(const std::string& output) {
  const size_t end = output.find_last_not_of(" \n\r\t");
  if (end == std::string::npos) return "(it printed nothing)";
  const size_t newline = output.rfind('\n', end);
  const size_t begin = newline == std::string::npos ? 0 : newline + 1;
  return output.substr(begin, end + 1 - begin);
}

// The child's environment: under AddressSanitizer, which takes no address-space limit, a cap on any
// single allocation instead (its report ends the child).
std::vector<std::string> child_environment(uint64_t budget) {
  if (!kAddressSanitizer) return {};
  const char* options = std::getenv("ASAN_OPTIONS");
  return {str("ASAN_OPTIONS=", options ? options : "", options && *options ? ":" : "",
              "max_allocation_size_mb=", budget >> 20)};
}

// What the child's end says about the file, as an Error naming it.
[[noreturn]] void fail_with_childs_end(const std::string& where, const std::string& format, const ProcessResult& r,
                                       unsigned seconds) {
  const std::string kErrorPrefix = "spume: error: ";
  if (r.exit_code == 1) {
    // The child's own message, which names the file: the reader's Error, said as the command says it.
    const size_t at = r.output.find(kErrorPrefix);
    if (at != std::string::npos) {
      const size_t begin = at + kErrorPrefix.size(), end = r.output.find('\n', begin);
      throw Error(r.output.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    }
  }
  if (r.signal == SIGABRT)
    fail(where, ": ", library_of(format), " stopped on one of its own checks while reading this file (it called "
         "abort()): it is damaged (or not written by ", library_of(format), ")");
  if (r.signal == SIGALRM)
    fail(where, ": reading this file did not end within ", seconds, " s (a sound file of its size reads in a small "
         "part of that): it is damaged");
  if (r.signal != 0)
    fail(where, ": reading this file ended spume's reader process with signal ", r.signal, " (", strsignal(r.signal),
         "): it is damaged");
  fail(where, ": reading this file stopped spume's reader process (exit status ", r.exit_code,
       "); it said: ", last_line(r.output));
}

}  // namespace

void contain_untrusted_reads(const std::filesystem::path& helper) {
  const std::lock_guard lock(g_mutex);
  g_helper = helper;
}

uint64_t contained_read_budget(uint64_t file_bytes) { return (uint64_t(256) << 20) + 64 * file_bytes; }

unsigned contained_read_seconds(uint64_t file_bytes) { return unsigned(60 + file_bytes / (50u << 20)); }

void check_read_in_child(const std::filesystem::path& path, const std::string& format, const std::string& grid_name) {
  std::filesystem::path helper;
  const std::string key = version_key(path, format, grid_name);
  {
    const std::lock_guard lock(g_mutex);
    if (g_helper.empty() || g_read_cleanly.count(key)) return;
    helper = g_helper;
  }
  const std::string where = path.string();
  std::error_code size_error;
  const uint64_t size = std::filesystem::file_size(path, size_error);
  const uint64_t file_bytes = size_error ? 0 : size;
  const uint64_t budget = contained_read_budget(file_bytes);
  const ProcessResult r = run_process({helper.string(), kReadCheckWord, format, where, grid_name},
                                      child_environment(budget));
  if (!r.started)
    fail(where, ": cannot start spume's reader process (", helper.string(), ": ", r.start_error,
         ") to read this file apart");
  if (r.exit_code != 0) fail_with_childs_end(where, format, r, contained_read_seconds(file_bytes));
  const std::lock_guard lock(g_mutex);
  g_read_cleanly.insert(key);
}

void limit_this_process_for_a_contained_read(uint64_t budget_bytes, unsigned seconds) {
  ::alarm(seconds);  // SIGALRM's default action ends the process; the parent names the file
  if (kAddressSanitizer) return;
  // The address space in use now (the first field of /proc/self/statm, in pages) plus the budget,
  // never above the limit the process already has.
  uint64_t pages = 0;
  std::ifstream("/proc/self/statm") >> pages;
  rlimit limit{};
  if (pages == 0 || getrlimit(RLIMIT_AS, &limit) != 0) return;
  const uint64_t wanted = pages * uint64_t(sysconf(_SC_PAGESIZE)) + budget_bytes;
  if (limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur <= wanted) return;
  limit.rlim_cur = rlim_t(wanted);
  // Only a limit of its own makes a failed allocation the budget's: under a lower one the process
  // already had, it is said as running out of memory, with that limit.
  if (setrlimit(RLIMIT_AS, &limit) == 0) g_budget_in_force = budget_bytes;
}

uint64_t read_budget_in_force() { return g_budget_in_force; }

}  // namespace spume

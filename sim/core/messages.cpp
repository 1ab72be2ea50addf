#include "sim/core/messages.h"

#include <cstdio>
#include <mutex>
#include <unordered_set>

namespace spume::messages {
namespace {

struct Stream {
  std::mutex mutex;
  bool quiet = false;
  bool open_line = false;  // an in-place progress line is on the terminal, without its newline
  std::vector<std::string> warnings;
  std::unordered_set<std::string> seen;
};

Stream& stream() {
  static Stream s;
  return s;
}

// Called with the mutex held.
void print_line(Stream& s, const std::string& line) {
  if (s.open_line) std::fputc('\n', stderr), s.open_line = false;
  std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
}

}  // namespace

void set_quiet(bool quiet) {
  std::lock_guard lock(stream().mutex);
  stream().quiet = quiet;
}

bool quiet() {
  std::lock_guard lock(stream().mutex);
  return stream().quiet;
}

bool is_warning(const std::string& line) { return line.rfind("warning:", 0) == 0; }

void note(const std::string& line) {
  Stream& s = stream();
  std::lock_guard lock(s.mutex);
  if (!s.quiet) print_line(s, line);
}

void warning(const std::string& line) {
  const std::string text = is_warning(line) ? line : kWarningPrefix + line;
  Stream& s = stream();
  std::lock_guard lock(s.mutex);
  if (!s.seen.insert(text).second) return;
  s.warnings.push_back(text);
  print_line(s, text);
}

void report(const std::string& line) {
  if (is_warning(line))
    warning(line);
  else
    note(line);
}

std::vector<std::string> warnings() { return warnings_since(0); }

std::vector<std::string> warnings_since(size_t from) {
  Stream& s = stream();
  std::lock_guard lock(s.mutex);
  if (from >= s.warnings.size()) return {};
  return {s.warnings.begin() + std::ptrdiff_t(from), s.warnings.end()};
}

void progress_line(const std::string& line, bool in_place) {
  Stream& s = stream();
  std::lock_guard lock(s.mutex);
  if (s.quiet) return;
  if (in_place) {
    std::fprintf(stderr, "\r\033[K%s", line.c_str());
    s.open_line = true;
  } else {
    print_line(s, line);
  }
  std::fflush(stderr);
}

void end_progress_line() {
  Stream& s = stream();
  std::lock_guard lock(s.mutex);
  if (s.open_line) std::fputc('\n', stderr), s.open_line = false;
}

void reset() {
  Stream& s = stream();
  std::lock_guard lock(s.mutex);
  s.quiet = false;
  s.warnings.clear();
  s.seen.clear();
}

}  // namespace spume::messages

#include "sim/core/atomic_file.h"

#include <cstdio>
#include <fstream>
#include <system_error>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>

#include "sim/core/direct_io.h"
#include "sim/core/error.h"

namespace spume {
namespace {

std::string host_name() {
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0 || !host[0]) std::snprintf(host, sizeof host, "unknown");
  return host;
}

// The temporary file's name beside `path` (unique per host and process), its folder made first.
std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) fail(path.string(), ": cannot create directory ", path.parent_path().string(), ": ", ec.message());
  }
  // Unique per host and process: farm nodes share output folders, and pids repeat across hosts.
  fs::path tmp = path;
  tmp += str(".tmp.", host_name(), ".", ::getpid());
  return tmp;
}

// Writes `path` through a temporary beside it: fill(tmp) writes the temporary (throwing Error when it
// cannot), which is then renamed into place; on any failure the temporary is removed.
void replace_atomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& fill) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path tmp = temporary_beside(path);
  try {
    fill(tmp);
    fs::rename(tmp, path, ec);
    if (ec) fail(path.string(), ": cannot rename temporary file into place: ", ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace

void write_bytes_atomically(const std::filesystem::path& path, const char* data, size_t size) {
  replace_atomically(path, [&](const std::filesystem::path& tmp) { write_file_bytes(tmp, data, size, path.string()); });
}

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  replace_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail(path.string(), ": cannot open ", tmp.string(), " for writing");
    write(out);
    out.flush();
    if (!out) fail(path.string(), ": write failed (disk full?)");
  });
}

int remove_dead_temporaries(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  const std::string here = host_name();
  int removed = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const size_t mark = name.rfind(".tmp.");
    const size_t last_dot = name.rfind('.');
    if (mark == std::string::npos || last_dot <= mark + 4) continue;
    const std::string host = name.substr(mark + 5, last_dot - mark - 5), pid_text = name.substr(last_dot + 1);
    if (host != here || pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::strtol(pid_text.c_str(), nullptr, 10);
    // Signal 0 only asks whether the process exists; ESRCH: it does not. (EPERM: it exists.)
    if (pid <= 0 || ::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;
    if (fs::remove(entry.path(), ec)) ++removed;
  }
  return removed;
}

}  // namespace spume

#include "sim/core/atomic_file.h"

#include <cstdio>
#include <fstream>
#include <system_error>
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>

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

constexpr size_t kDirectAlignment = 4096;  // covers 512- and 4096-byte logical blocks

// Writes [data, data + size) at the file's current offset; false (errno set) on failure.
bool write_all(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t wrote = ::write(fd, data, std::min<size_t>(size, size_t(1) << 30));
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) return false;
    data += wrote, size -= size_t(wrote);
  }
  return true;
}

}  // namespace

void write_bytes_atomically(const std::filesystem::path& path, const char* data, size_t size) {
  namespace fs = std::filesystem;
  const fs::path tmp = temporary_beside(path);
  const bool aligned = reinterpret_cast<uintptr_t>(data) % kDirectAlignment == 0;
  const size_t direct = aligned ? size / kDirectAlignment * kDirectAlignment : 0;
  const int flags = O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC;
  int fd = direct > 0 ? ::open(tmp.c_str(), flags | O_DIRECT, 0666) : -1;
  const bool is_direct = fd >= 0;
  if (fd < 0) fd = ::open(tmp.c_str(), flags, 0666);
  if (fd < 0) fail(path.string(), ": cannot open ", tmp.string(), " for writing: ", std::strerror(errno));
  std::error_code ec;
  auto give_up = [&](const char* what) {
    const int error = errno;
    ::close(fd);
    fs::remove(tmp, ec);
    fail(path.string(), ": ", what, ": ", std::strerror(error));
  };
  size_t done = 0;
  if (is_direct) {
    if (write_all(fd, data, direct)) {
      done = direct;
    } else if (errno != EINVAL) {
      give_up("write failed (disk full?)");
    }
    // The tail (and, where direct writes were refused, everything) through the page cache.
    if (::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_DIRECT) != 0) give_up("cannot leave direct I/O");
    if (done == 0 && ::lseek(fd, 0, SEEK_SET) != 0) give_up("cannot rewind");
  }
  if (!write_all(fd, data + done, size - done)) give_up("write failed (disk full?)");
  if (::close(fd) != 0) {
    fs::remove(tmp, ec);
    fail(path.string(), ": write failed (disk full?): ", std::strerror(errno));
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    fail(path.string(), ": cannot rename temporary file into place: ", ec.message());
  }
}

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path tmp = temporary_beside(path);
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail(path.string(), ": cannot open ", tmp.string(), " for writing");
    write(out);
    out.flush();
    if (!out) fail(path.string(), ": write failed (disk full?)");
    out.close();
    fs::rename(tmp, path, ec);
    if (ec) fail(path.string(), ": cannot rename temporary file into place: ", ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
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

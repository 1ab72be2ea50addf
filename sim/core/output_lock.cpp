#include "sim/core/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/core/stopwatch.h"

namespace spume {
namespace {

int open_lock_file(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) fail(path.string(), ": cannot open the lock file (", std::strerror(errno), ")");
  return fd;
}

// The lock file lives in the output folder: a folder that cannot be made or written to is named as
// such, with the system's reason, rather than as a lock file that cannot be opened.
void require_writable_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) fail(dir.string(), ": cannot create the output folder (", ec.message(), ")");
  if (!std::filesystem::is_directory(dir, ec)) fail(dir.string(), ": the output folder is a file, not a folder");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    fail(dir.string(), ": cannot write in the output folder (", std::strerror(errno), ")");
}

// Holds the gate for one look at the lock.
class Gate {
 public:
  explicit Gate(const std::filesystem::path& path) : fd_(open_lock_file(path)) {
    while (::flock(fd_, LOCK_EX) != 0)
      if (errno != EINTR) fail(path.string(), ": cannot lock (", std::strerror(errno), ")");
  }
  ~Gate() { ::close(fd_); }  // closing releases the flock

 private:
  int fd_;
};

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

void update_under_gate(const std::filesystem::path& dir, const std::function<void()>& update) {
  Gate gate(dir / ".lock.gate");
  update();
}

OutputLock::OutputLock(const std::filesystem::path& dir, Mode mode, const std::string& keys, const std::string& what,
                       bool quiet) {
  require_writable_folder(dir);
  const auto lock_path = dir / ".lock", gate_path = dir / ".lock.gate", keys_path = dir / ".lock.keys";
  fd_ = open_lock_file(lock_path);
  // First line: the holders' keys, which a sharer must match; second: who holds it, for messages.
  const std::string ours = (mode == Mode::Exclusive ? "exclusive " + std::to_string(::getpid()) : "shared " + keys);
  const std::string holder = what + " (pid " + std::to_string(::getpid()) + ")";
  bool told = false;
  const Stopwatch waited;
  for (;;) {
    {
      Gate gate(gate_path);
      if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) {
        // Nobody holds it: ours, with our keys on record.
        write_file_atomically(keys_path, [&](std::ostream& out) { out << ours << '\n' << holder << '\n'; });
        if (mode == Mode::Shared) ::flock(fd_, LOCK_SH);  // under the gate: nobody can slip in between
        break;
      }
      const std::string held = read_text(keys_path);
      const std::string held_keys = held.substr(0, held.find('\n'));
      if (mode == Mode::Shared && held_keys == ours && ::flock(fd_, LOCK_SH | LOCK_NB) == 0) break;
      if (!told && !quiet) {
        const size_t at = held.find('\n');
        const std::string who = at == std::string::npos ? "another spume" : held.substr(at + 1, held.find('\n', at + 1) - at - 1);
        std::fprintf(stderr, "waiting for %s, which is writing %s%s\n", who.c_str(), dir.string().c_str(),
                     held_keys.rfind("shared ", 0) == 0 && mode == Mode::Shared ? " with other render keys" : "");
        told = true;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  if (told && !quiet)
    std::fprintf(stderr, "%s is free after %.1f s\n", dir.string().c_str(), waited.seconds());
}

OutputLock::~OutputLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace spume

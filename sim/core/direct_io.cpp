#include "sim/core/direct_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>

#include "sim/core/error.h"

namespace spume {
namespace {

constexpr size_t kDirectAlignment = 4096;  // covers 512- and 4096-byte logical blocks

// Moves up to `size` bytes at the file's offset with `step` (read or write); the count moved (short
// only at the end of a file being read), or -1 with errno set.
template <typename Step>
ptrdiff_t move_all(int fd, char* data, size_t size, Step&& step) {
  size_t done = 0;
  while (done < size) {
    const ssize_t moved = step(fd, data + done, std::min<size_t>(size - done, size_t(1) << 30));
    if (moved < 0 && errno == EINTR) continue;
    if (moved < 0) return -1;
    if (moved == 0) break;
    done += size_t(moved);
  }
  return ptrdiff_t(done);
}

// Moves `size` bytes between the file (opened with `flags`) and data: the whole blocks directly when
// data is aligned and the file system takes it, then the rest (or, where refused, everything) through
// the page cache. A short move is an error, `short_move` its message.
template <typename Step>
void move_file(const std::filesystem::path& path, int flags, char* data, size_t size, const std::string& where,
               const char* failed, const char* short_move, Step&& step) {
  const bool aligned = reinterpret_cast<uintptr_t>(data) % kDirectAlignment == 0;
  const size_t direct = aligned ? size / kDirectAlignment * kDirectAlignment : 0;
  int fd = direct > 0 ? ::open(path.c_str(), flags | O_DIRECT, 0666) : -1;
  const bool is_direct = fd >= 0;
  if (fd < 0) fd = ::open(path.c_str(), flags, 0666);
  if (fd < 0) fail(where, ": cannot open ", path.string(), ": ", std::strerror(errno));
  auto give_up = [&](const char* what) {
    const int error = errno;
    ::close(fd);
    fail(where, ": ", what, error ? ": " : "", error ? std::strerror(error) : "");
  };
  auto check = [&](ptrdiff_t moved, size_t wanted) {
    if (moved < 0) give_up(failed);
    if (size_t(moved) != wanted) errno = 0, give_up(short_move);
  };
  size_t done = 0;
  if (is_direct) {
    const ptrdiff_t moved = move_all(fd, data, direct, step);
    if (moved >= 0 || errno != EINVAL) check(moved, direct), done = direct;
    // The tail (and, where direct I/O was refused, everything) through the page cache.
    if (::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_DIRECT) != 0) give_up("cannot leave direct I/O");
    if (done == 0 && ::lseek(fd, 0, SEEK_SET) != 0) give_up("cannot rewind");
  }
  check(move_all(fd, data + done, size - done, step), size - done);
  errno = 0;
  if (::close(fd) != 0) fail(where, ": ", failed, ": ", std::strerror(errno));
}

}  // namespace

void read_file_bytes(const std::filesystem::path& path, char* data, size_t size) {
  move_file(path, O_RDONLY | O_CLOEXEC, data, size, path.string(), "read failed",
            "read failed (file changed or unreadable)", [](int fd, char* p, size_t n) { return ::read(fd, p, n); });
}

void write_file_bytes(const std::filesystem::path& path, const char* data, size_t size, const std::string& where) {
  // The write step never stores through the pointer; the shared mover takes char* for both directions.
  move_file(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, const_cast<char*>(data), size, where,
            "write failed (disk full?)", "write failed (disk full?)",
            [](int fd, char* p, size_t n) { return ::write(fd, p, n); });
}

}  // namespace spume

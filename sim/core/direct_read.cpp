#include "sim/core/direct_read.h"

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

// Reads up to `size` bytes at the file's offset; the count read (short only at the end of the file),
// or -1 with errno set.
ptrdiff_t read_all(int fd, char* data, size_t size) {
  size_t done = 0;
  while (done < size) {
    const ssize_t got = ::read(fd, data + done, std::min<size_t>(size - done, size_t(1) << 30));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return -1;
    if (got == 0) break;
    done += size_t(got);
  }
  return ptrdiff_t(done);
}

}  // namespace

void read_file_bytes(const std::filesystem::path& path, char* data, size_t size) {
  const bool aligned = reinterpret_cast<uintptr_t>(data) % kDirectAlignment == 0;
  const size_t direct = aligned ? size / kDirectAlignment * kDirectAlignment : 0;
  int fd = direct > 0 ? ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_DIRECT) : -1;
  const bool is_direct = fd >= 0;
  if (fd < 0) fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(path.string(), ": cannot open for reading: ", std::strerror(errno));
  auto give_up = [&](const char* what) {
    const int error = errno;
    ::close(fd);
    fail(path.string(), ": ", what, error ? ": " : "", error ? std::strerror(error) : "");
  };
  size_t done = 0;
  if (is_direct) {
    const ptrdiff_t got = read_all(fd, data, direct);
    if (got < 0 && errno != EINVAL) give_up("read failed");
    if (got >= 0 && size_t(got) < direct) {
      errno = 0;
      give_up("read failed (file changed or unreadable)");
    }
    if (got >= 0) done = direct;
    // The tail (and, where direct reads were refused, everything) through the page cache.
    if (::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_DIRECT) != 0) give_up("cannot leave direct I/O");
    if (done == 0 && ::lseek(fd, 0, SEEK_SET) != 0) give_up("cannot rewind");
  }
  const ptrdiff_t got = read_all(fd, data + done, size - done);
  if (got < 0) give_up("read failed");
  errno = 0;
  if (size_t(got) != size - done) give_up("read failed (file changed or unreadable)");
  ::close(fd);
}

}  // namespace spume

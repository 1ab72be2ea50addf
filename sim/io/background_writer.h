#pragma once
// Writes files on a thread of its own, one at a time, so that the simulation goes on while a frame's
// cache goes to the disk (a 14M-particle frame: 170 MB; through the page cache that was about 0.4 s of
// write() on this VM, against 0.55 s to encode it). Each file is written atomically, its whole blocks
// past the page cache (core/atomic_file.h, write_bytes_atomically).
#include <filesystem>
#include <future>

#include "sim/io/column_codec.h"

namespace spume {

class BackgroundWriter {
 public:
  BackgroundWriter() = default;
  BackgroundWriter(const BackgroundWriter&) = delete;
  BackgroundWriter& operator=(const BackgroundWriter&) = delete;
  // Waits for the file in flight. Its error, if any, is dropped: a caller that did not wait() is
  // already unwinding from another error, and never marks the stage finished.
  ~BackgroundWriter();

  // Waits for the previous file, then starts writing `bytes` to `path`; returns the milliseconds spent
  // waiting. If the previous file failed, throws its error instead, and `path` is not written.
  double write(std::filesystem::path path, CacheBytes bytes);
  // Waits until the file in flight is on disk (in the page cache, renamed into place); rethrows its
  // error. Returns the milliseconds spent waiting.
  double wait();

 private:
  std::future<void> pending_;
};

}  // namespace spume

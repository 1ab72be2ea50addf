#include "sim/io/background_writer.h"

#include <ostream>
#include <utility>

#include "sim/core/atomic_file.h"
#include "sim/core/stopwatch.h"

namespace spume {

BackgroundWriter::~BackgroundWriter() {
  if (pending_.valid()) pending_.wait();
}

double BackgroundWriter::write(std::filesystem::path path, CacheBytes bytes) {
  const double waited = wait();
  // The bytes move into the task's own scope, so that their memory goes back to the pool when the file
  // is written, not when the next file replaces this future (the next frame's encoding wants it).
  pending_ = std::async(std::launch::async, [path = std::move(path), bytes = std::move(bytes)]() mutable {
    const CacheBytes mine = std::move(bytes);
    write_bytes_atomically(path, mine.data(), mine.size());
  });
  return waited;
}

double BackgroundWriter::wait() {
  if (!pending_.valid()) return 0.0;
  const Stopwatch watch;
  std::future<void> done = std::move(pending_);
  done.get();  // rethrows the writer's error
  return watch.milliseconds();
}

}  // namespace spume

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
  pending_ = std::async(std::launch::async, [path = std::move(path), bytes = std::move(bytes)] {
    write_bytes_atomically(path, bytes.data(), bytes.size());
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

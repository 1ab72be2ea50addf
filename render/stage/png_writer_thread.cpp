#include "render/stage/png_writer_thread.h"

#include <utility>

#include "render/image/png_io.h"
#include "sim/core/stopwatch.h"

namespace spume {
namespace {

double timed_write(const std::filesystem::path& path, const ImageRGB8& image, const std::string& record) {
  const Stopwatch watch;
  write_png(path, image, record);
  return watch.seconds();
}

}  // namespace

PngWriterThread::~PngWriterThread() {
  if (pending_.valid()) pending_.wait();
}

void PngWriterThread::write(std::filesystem::path path, ImageRGB8 image, std::string record, Done done) {
  finish();
  if (!background_) {
    done(timed_write(path, image, record));
    return;
  }
  done_ = std::move(done);
  pending_ = std::async(std::launch::async, [path = std::move(path), image = std::move(image), record = std::move(record)] {
    return timed_write(path, image, record);
  });
}

void PngWriterThread::finish() {
  if (!pending_.valid()) return;
  std::future<double> written = std::move(pending_);
  Done done = std::move(done_);
  done(written.get());
}

}  // namespace spume

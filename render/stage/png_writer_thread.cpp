#include "render/stage/png_writer_thread.h"

#include <utility>

#include "render/image/png_io.h"
#include "sim/core/stopwatch.h"

namespace spume {
namespace {

double timed_write(const std::filesystem::path& path, const ImageRGB8& image, const std::string& record,
                   const std::function<void()>& before) {
  const Stopwatch watch;
  if (before) before();
  write_png(path, image, record);
  return watch.seconds();
}

}  // namespace

PngWriterThread::~PngWriterThread() {
  if (pending_.valid()) pending_.wait();
}

void PngWriterThread::write(std::filesystem::path path, ImageRGB8 image, std::string record,
                            std::function<void()> before, Done done) {
  finish();
  if (!background_) {
    done(timed_write(path, image, record, before));
    return;
  }
  done_ = std::move(done);
  pending_ = std::async(std::launch::async, [path = std::move(path), image = std::move(image), record = std::move(record),
                                             before = std::move(before)] { return timed_write(path, image, record, before); });
}

void PngWriterThread::finish() {
  if (!pending_.valid()) return;
  std::future<double> written = std::move(pending_);
  Done done = std::move(done_);
  done(written.get());
}

}  // namespace spume

#pragma once
// Writes each frame's PNG on a thread of its own while the next frame renders: a 1080p frame is about
// 80 ms of deflate on one core, which then overlaps the next frame's work. One file at a time, each
// written atomically (write_png); what follows a file being on disk (its row of render_stats.csv,
// "Saved:") runs on the caller's thread once it is, in frame order.
#include <filesystem>
#include <functional>
#include <future>
#include <string>

#include "render/image/image.h"

namespace spume {

class PngWriterThread {
 public:
  using Done = std::function<void(double write_seconds)>;

  // background false: each file is written in write() itself (for --threads 1).
  explicit PngWriterThread(bool background) : background_(background) {}
  PngWriterThread(const PngWriterThread&) = delete;
  PngWriterThread& operator=(const PngWriterThread&) = delete;
  ~PngWriterThread();  // waits for the file in flight; its error and its `done` are dropped

  // finish()es the previous file, then runs `before` (another file of the frame, or nothing) and writes
  // this one; `done` runs once both are on disk, with the seconds they took.
  void write(std::filesystem::path path, ImageRGB8 image, std::string record, std::function<void()> before, Done done);
  // Waits for the file in flight and runs its `done`; rethrows its error (which names the file).
  void finish();

 private:
  bool background_;
  std::future<double> pending_;  // the write's seconds
  Done done_;
};

}  // namespace spume

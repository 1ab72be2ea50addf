#include "render/stage/frame_prefetch.h"

#include "sim/core/stopwatch.h"

namespace spume {
namespace {

TakenFrame timed_load(PreparedRender& prepared, int frame) {
  const Stopwatch watch;
  TakenFrame taken{load_frame(prepared, frame)};
  taken.load_seconds = watch.seconds();
  return taken;
}

}  // namespace

FramePrefetch::~FramePrefetch() {
  if (pending_.valid()) pending_.wait();
}

void FramePrefetch::start(int frame) {
  if (!ahead_ || pending_.valid()) return;
  pending_frame_ = frame;
  pending_ = std::async(std::launch::async, [this, frame] { return timed_load(prepared_, frame); });
}

TakenFrame FramePrefetch::take(int frame) {
  if (pending_.valid()) {
    std::future<TakenFrame> done = std::move(pending_);
    if (pending_frame_ == frame) return done.get();
    done.wait();  // a frame nobody asked for after all: dropped, and its error with it
  }
  return timed_load(prepared_, frame);
}

}  // namespace spume

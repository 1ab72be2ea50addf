#pragma once
// Loads the next frame to draw on a thread of its own while the current one renders: reading and
// decoding a 15M-particle frame takes about 0.1 s, which then overlaps the render's less parallel
// parts (the OSMesa pass, the PNG). One load at a time; a frame not asked for ahead is loaded when
// taken. The loaded frame is the same either way, and so is every picture.
#include <future>

#include "render/stage/render_stage.h"

namespace spume {

struct TakenFrame {
  LoadedFrame frame;
  double load_seconds = 0.0;  // the load's own time, wherever it ran
};

class FramePrefetch {
 public:
  // ahead false: every frame is loaded when taken (one thread of work, for --threads 1).
  FramePrefetch(PreparedRender& prepared, bool ahead) : prepared_(prepared), ahead_(ahead) {}
  FramePrefetch(const FramePrefetch&) = delete;
  FramePrefetch& operator=(const FramePrefetch&) = delete;
  ~FramePrefetch();  // waits for a load in flight; its error is dropped (the caller is unwinding)

  // Starts loading `frame` unless a load is in flight or prefetching is off.
  void start(int frame);
  // `frame` loaded: the prefetched one when it is that frame, else loaded now. Rethrows the load's
  // error, which names the frame.
  TakenFrame take(int frame);

 private:
  PreparedRender& prepared_;
  bool ahead_;
  std::future<TakenFrame> pending_;
  int pending_frame_ = -1;
};

}  // namespace spume

#pragma once
// The exact integrator's candidate search: every drawn sphere is projected through the pinhole
// camera and binned into the 32x32-pixel bins its projection touches, together with the pixel
// rectangle whose sample points can see it. A tile then tests each of its spheres only against the
// rays of that rectangle (about 4/pi tests per chord found: a disc in its bounding box), with no
// 3D traversal at all, and feeds them near to far so each ray's chords arrive almost sorted.
// Binning is a two-pass counting sort over fixed chunks of particles, so tile lists (and images)
// do not depend on the thread count.
#include <array>
#include <cstdint>
#include <vector>

#include "render/camera/camera.h"
#include "sim/core/frames.h"
#include "sim/core/huge_page_array.h"

namespace spume {

// Camera constants for projecting spheres to conservative pixel rectangles.
class SphereProjector {
 public:
  // jitter_lo/hi: the range of a sample's offset inside its pixel (0.5/0.5 for pixel centres).
  SphereProjector(const Camera& camera, double jitter_lo, double jitter_hi);
  // Inclusive pixel rectangle of the pixels with a sample point that may see the sphere; false
  // when none (behind the camera, outside the frustum or off the image). A sphere reaching the
  // camera plane projects unboundedly and gets the whole image.
  // Float arithmetic (it runs once per particle): rounding is ~1e-4 pixel, inside the margin.
  bool pixel_rect(const Vec3f& centre, float radius, int& x0, int& y0, int& x1, int& y1) const;
  // pixel_rect for n <= kBatch spheres at once, the same arithmetic without branches so the
  // compiler runs it four lanes wide, eight with AVX2 (it was a fifth of binning 15M spheres; with
  // AVX2, bench_volume's bins at 15M took 0.48x the time). A radius <= 0 or a sphere pixel_rect
  // rejects gets x0 > x1.
  static constexpr size_t kBatch = 64;
  struct Rects {
    int x0[kBatch], y0[kBatch], x1[kBatch], y1[kBatch];
  };
  void pixel_rects(const Vec3f* centres, const float* radii, size_t n, Rects& out) const;

 private:
  // pixel_rects' loop, compiled for SSE2 (x86-64's baseline) and, where the processor has it, AVX2:
  // eight lanes instead of four, the same IEEE operations in each lane, so the same rectangles.
  void pixel_rects_loop(const Vec3f* centres, const float* radii, size_t n, Rects& out) const;
  void pixel_rects_avx2(const Vec3f* centres, const float* radii, size_t n, Rects& out) const;

  Vec3f origin_, right_, up_, forward_;
  float tan_x_, tan_y_;     // half-extents of the image plane at unit depth
  float cull_x_, cull_y_;   // 1 / |side plane normal| for frustum culling
  float scale_x_, scale_y_; // pixels per unit of image plane at unit depth
  int width_, height_;
  float lo_margin_, hi_margin_;  // pixel-rectangle rounding: margin plus the jitter range
};

// A sphere in a list: centre and, packed, its type and the pixel rectangle it may be seen in,
// inclusive and relative to the list's bin (or, in the volume pass, to one 16x16 tile of it).
struct BinnedSphere {
  float x, y, z;
  uint32_t packed;  // bits 0-4 x0, 5-9 x1, 10-14 y0, 15-19 y1, 20-21 type

  static BinnedSphere make(const Vec3f& c, uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1, uint32_t type) {
    return {c.x(), c.y(), c.z(), x0 | (x1 << 5) | (y0 << 10) | (y1 << 15) | (type << 20)};
  }
  Vec3f centre() const { return Vec3f(x, y, z); }
  int x0() const { return int(packed & 31u); }
  int x1() const { return int((packed >> 5) & 31u); }
  int y0() const { return int((packed >> 10) & 31u); }
  int y1() const { return int((packed >> 15) & 31u); }
  uint32_t type() const { return (packed >> 20) & 3u; }
};

class ScreenBins {
 public:
  // Bins of 32x32 pixels, each traced as 2x2 tiles of 16x16. Larger bins than tiles: a sphere
  // lands in fewer bins (about 1.2 per sphere at 1080p and 15M spheres, against 1.4 for 16-pixel
  // bins), and the binning writes to four times fewer places at once, so its partly written cache
  // lines stay in cache: the scatter was memory-bound.
  static constexpr int kBin = 32;
  static constexpr int kTile = 16;  // pixels; the volume pass's tiles

  // The entry array outlives the bins: the next ScreenBins in the process (the next frame) reuses
  // it when it is large enough. At 15M spheres the kernel's zeroing of its fresh pages (~290 MB)
  // was a seventh of the pass's CPU time; frames after the first skip it. Thread-safe.
  ScreenBins(DiffuseView frame, const std::array<float, kDiffuseTypeCount>& radius, const SphereProjector& projector,
             int width, int height);
  ~ScreenBins();
  ScreenBins(const ScreenBins&) = delete;
  ScreenBins& operator=(const ScreenBins&) = delete;

  int bins_x() const { return bins_x_; }
  int bins_y() const { return bins_y_; }
  const BinnedSphere* begin(size_t bin) const { return entries_.data() + bin_start_[bin]; }
  const BinnedSphere* end(size_t bin) const { return entries_.data() + bin_start_[bin + 1]; }
  size_t entry_count() const { return entries_.size(); }
  size_t memory_bytes() const { return entries_.size() * sizeof(BinnedSphere) + bin_start_.size() * sizeof(size_t); }

 private:
  int bins_x_, bins_y_;
  std::vector<size_t> bin_start_;  // bins + 1 offsets into entries_
  HugePageArray<BinnedSphere> entries_;
};

}  // namespace spume

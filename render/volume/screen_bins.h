#pragma once
// The exact integrator's candidate search: every drawn sphere is projected through the pinhole
// camera and binned into the 16x16-pixel tiles its projection touches, together with the pixel
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
#include "render/volume/huge_buffer.h"

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

 private:
  Vec3f origin_, right_, up_, forward_;
  float tan_x_, tan_y_;     // half-extents of the image plane at unit depth
  float cull_x_, cull_y_;   // 1 / |side plane normal| for frustum culling
  float scale_x_, scale_y_; // pixels per unit of image plane at unit depth
  int width_, height_;
  float lo_margin_, hi_margin_;  // pixel-rectangle rounding: margin plus the jitter range
};

// A sphere in one tile's list: centre and, packed, its type and the tile-local pixel rectangle.
struct BinnedSphere {
  float x, y, z;
  uint32_t packed;  // bits 0-3 x0, 4-7 x1, 8-11 y0, 12-15 y1 (tile-local, inclusive), 16-17 type

  Vec3f centre() const { return Vec3f(x, y, z); }
  int x0() const { return int(packed & 15u); }
  int x1() const { return int((packed >> 4) & 15u); }
  int y0() const { return int((packed >> 8) & 15u); }
  int y1() const { return int((packed >> 12) & 15u); }
  uint32_t type() const { return (packed >> 16) & 3u; }
};

class ScreenBins {
 public:
  static constexpr int kTile = 16;  // pixels; the volume pass uses the same tiles

  ScreenBins(const DiffuseFrame& frame, const std::array<float, kDiffuseTypeCount>& radius, const SphereProjector& projector,
             int width, int height);

  int tiles_x() const { return tiles_x_; }
  int tiles_y() const { return tiles_y_; }
  const BinnedSphere* begin(size_t tile) const { return entries_.data() + tile_start_[tile]; }
  const BinnedSphere* end(size_t tile) const { return entries_.data() + tile_start_[tile + 1]; }
  size_t entry_count() const { return entries_.size(); }
  size_t memory_bytes() const { return entries_.size() * sizeof(BinnedSphere) + tile_start_.size() * sizeof(size_t); }

 private:
  int tiles_x_, tiles_y_;
  std::vector<size_t> tile_start_;  // tiles + 1 offsets into entries_
  HugeBuffer<BinnedSphere> entries_;
};

}  // namespace spume

#pragma once
// The eye rays of one 16x16 pixel tile: jittered sample positions, the diffuse bounds' entry and
// exit, the first opaque hit (which ends the ray) and the stretches in water.
#include <cstdint>
#include <vector>

#include "render/camera/camera.h"
#include "render/volume/absorption.h"
#include "render/volume/water_path.h"

namespace spume {

class SurfaceScene;

// Offset of sample `sample` inside pixel `pixel` (row-major index), in [0, 1)^2: the centre for
// one sample per pixel, else a counter-based Philox draw of (seed, frame, pixel, sample), so every
// pixel gets the same rays whatever thread renders it.
void sample_offset(uint64_t seed, int frame, uint64_t pixel, uint32_t sample, int samples_per_pixel, float& u, float& v);

// Camera::ray's direction with the camera basis and tangent computed once instead of per ray
// (they were a tenth of the trace at 1M spheres): the same float expressions in the same order, so
// the same bits (tests/render/volume_exact_test.cpp checks it against Camera::ray).
class EyeRayDirections {
 public:
  explicit EyeRayDirections(const Camera& camera);
  Vec3f operator()(float px, float py) const {
    const float sx = (2.0f * px / float(width_) - 1.0f) * tan_half_ * aspect_;
    const float sy = (1.0f - 2.0f * py / float(height_)) * tan_half_;
    return (sx * right_ + sy * true_up_ - back_).normalized();
  }

 private:
  Vec3f right_, true_up_, back_;
  float tan_half_, aspect_;
  int width_, height_;
};

struct TileRay {
  Vec3f direction_f;      // Camera::ray's float direction (for Embree)
  Vec3d direction;        // the same, normalised in double (for exact chords)
  double t_in = 1.0;      // m; entry into the diffuse bounds (>= 0); also the intervals' reference
  double t_out = 0.0;     // m; exit from the bounds or the first opaque hit, whichever is nearer
  uint32_t water_begin = 0, water_end = 0;  // its WaterSegments in TileRays::water (relative to t_in)

  bool misses() const { return !(t_in < t_out); }
};

struct TileRays {
  int x0 = 0, y0 = 0, w = 0, h = 0, spp = 1;  // tile origin and size in pixels
  std::vector<TileRay> rays;                 // index (ly * w + lx) * spp + sample
  std::vector<WaterSegment> water;
  std::vector<WaterCrossing> crossings;      // scratch
};

struct TileRayParams {
  const Camera* camera;
  Vec3d bounds_lo, bounds_hi;  // m; every drawn sphere lies inside
  const SurfaceScene* surfaces;
  uint64_t seed;
  int frame;
  int samples_per_pixel;
};

// The rays of the w x h tile at (x0, y0). With `wanted` (one flag a ray, in the rays' order), a ray
// whose flag is 0 is left out, as a miss, and never traced against the surfaces.
void make_tile_rays(const TileRayParams& p, int x0, int y0, int w, int h, TileRays& out, const uint8_t* wanted = nullptr);

// The water stretches of ray r of t.
inline WaterView water_of(const TileRays& t, const TileRay& r) {
  return {t.water.data() + r.water_begin, size_t(r.water_end - r.water_begin)};
}

}  // namespace spume

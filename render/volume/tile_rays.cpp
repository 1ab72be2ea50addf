#include "render/volume/tile_rays.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/core/rng.h"
#include "render/volume/embree_scene.h"
#include "render/volume/ray_sphere.h"

namespace spume {

void sample_offset(uint64_t seed, int frame, uint64_t pixel, uint32_t sample, int samples_per_pixel, float& u, float& v) {
  if (samples_per_pixel <= 1) {
    u = v = 0.5f;  // the pixel centre, where the OSMesa background is sampled too
    return;
  }
  // The key constant keeps these draws apart from the simulator's streams under the same seed.
  const std::array<uint32_t, 2> key = {uint32_t(seed) ^ 0x7A3C51E9u, uint32_t(seed >> 32) ^ 0x0EE5E5EDu};
  const auto bits = philox4x32({uint32_t(pixel), uint32_t(pixel >> 32), sample, uint32_t(frame)}, key);
  u = to_unit_float(bits[0]);
  v = to_unit_float(bits[1]);
}

EyeRayDirections::EyeRayDirections(const Camera& camera) : width_(camera.width), height_(camera.height) {
  camera.basis(right_, true_up_, back_);
  tan_half_ = std::tan(0.5f * camera.fov_y_degrees * std::numbers::pi_v<float> / 180.0f);
  aspect_ = float(camera.width) / float(camera.height);
}

void make_tile_rays(const TileRayParams& p, int x0, int y0, int w, int h, TileRays& out, const uint8_t* wanted) {
  const Camera& cam = *p.camera;
  const int spp = p.samples_per_pixel;
  out.x0 = x0, out.y0 = y0, out.w = w, out.h = h, out.spp = spp;
  out.rays.resize(size_t(w) * size_t(h) * size_t(spp));
  out.water.clear();
  const Vec3d origin = cam.position.cast<double>();
  const EyeRayDirections eye(cam);
  for (int ly = 0; ly < h; ++ly)
    for (int lx = 0; lx < w; ++lx)
      for (int s = 0; s < spp; ++s) {
        const size_t index = (size_t(ly) * size_t(w) + size_t(lx)) * size_t(spp) + size_t(s);
        TileRay& r = out.rays[index];
        if (wanted && !wanted[index]) {
          r.direction_f = Vec3f::Zero(), r.direction = Vec3d::Zero();
          r.t_in = 1.0, r.t_out = 0.0;  // a miss
          r.water_begin = r.water_end = uint32_t(out.water.size());
          continue;
        }
        const uint64_t pixel = uint64_t(y0 + ly) * uint64_t(cam.width) + uint64_t(x0 + lx);
        float u, v;
        sample_offset(p.seed, p.frame, pixel, uint32_t(s), spp, u, v);
        const Ray ray{cam.position, eye(float(x0 + lx) + u, float(y0 + ly) + v)};
        r.direction_f = ray.direction;
        r.direction = unit_double(ray.direction);
        r.water_begin = r.water_end = uint32_t(out.water.size());
        if (!ray_box(origin, r.direction, p.bounds_lo, p.bounds_hi, r.t_in, r.t_out)) {
          r.t_in = 1.0, r.t_out = 0.0;
          continue;
        }
        // Only rays that reach the diffuse bounds need the surfaces.
        if (p.surfaces && !p.surfaces->empty()) {
          out.crossings.clear();
          r.t_out = std::min(r.t_out, p.surfaces->trace(ray.origin, ray.direction, r.t_out, r.t_in, out.crossings));
          if (!out.crossings.empty()) {
            thread_local std::vector<WaterSegment> seg;
            water_segments(out.crossings, -r.t_in, seg);
            out.water.insert(out.water.end(), seg.begin(), seg.end());
            r.water_end = uint32_t(out.water.size());
          }
        }
      }
}

}  // namespace spume

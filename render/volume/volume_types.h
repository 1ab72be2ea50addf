#pragma once
// Inputs and outputs of the absorption-only volume pass (MODEL.md §6, Eq. 9). Plain structs: the
// scene-file reader fills them, the pass never sees JSON.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sim/core/frames.h"
#include "sim/core/vec.h"
#include "render/keys/render_keys.h"

namespace spume {

struct TriangleMesh;

// How the length of a ray inside the diffuse material is found.
enum class VolumeIntegrator : uint8_t {
  March,  // Eq. 9 as written: delta(x) sampled every march_step from the bounds entry
  Exact,  // the march_step -> 0 limit: the length of the ray inside the union of spheres
};

// Where the exact integrator gets its ray/sphere candidates. Both compute every chord in double and
// give the same image up to float rounding of the interval ends; ScreenBins is 10-20x faster on
// 1M-15M spheres (tests/bench/bench_volume.cpp) and needs no BVH.
enum class ExactMethod : uint8_t {
  ScreenBins,     // spheres binned by the 32x32 pixel bins their projections touch
  EmbreeAllHits,  // Embree sphere points with a filter that records every hit and rejects it
};

// How one diffuse type is drawn.
struct DiffuseLook {
  float radius = 0.0f;              // m; r_d of Eq. 9. 0 = type not drawn (no spheres are built)
  Vec3f color = Vec3f::Ones();      // linear RGB, C_d of this type
};

struct VolumeSettings {
  std::array<DiffuseLook, kDiffuseTypeCount> look{};  // indexed by DiffuseType
  float alpha = float(keys::render::alpha.value[0]);  // 1/m; absorption scale of Eq. 9
  // 1/m per channel. Material seen through the water surface has its colour multiplied by
  // exp(-water_sigma * distance the eye ray has travelled in water); its opacity is unchanged. The
  // surface pass's absorption (render.water.absorption), so bubbles dim as the water around them does.
  Vec3f water_sigma = declared_vec3<Vec3f>(keys::render::water_absorption);
  VolumeIntegrator integrator = VolumeIntegrator::Exact;
  ExactMethod exact_method = ExactMethod::ScreenBins;
  float march_step = float(keys::render::march_step.value[0]);  // m; Eq. 9's Delta x. <= 0: half the smallest r_d
  int samples_per_pixel = int(keys::render::spp.value[0]);  // 1 = pixel centre; more = jittered, averaged
  uint64_t seed = uint64_t(keys::render::seed.value[0]);  // jitter key, with the frame, pixel and sample
  bool split_types = false;  // also each type's part of the image (VolumeImage::type_*), for EXR layers
  // Motion blur (swept_trace.h): the shutter in frame intervals, centred on the frame's time, and what
  // the caller knows of the scene: the frame interval (s; 0 = no blur) and gravity (spray's paths).
  float shutter = float(keys::render::shutter.value[0]);
  double frame_seconds = 0.0;
  Vec3f gravity = Vec3f(0.0f, -9.81f, 0.0f);

  bool blurs() const { return shutter > 0.0f && frame_seconds > 0.0; }

  bool drawn(DiffuseType t) const { return look[size_t(t)].radius > 0.0f; }
};

// The geometry the eye rays meet besides the diffuse spheres. Either may be null or empty.
struct VolumeSurfaces {
  // Fluid surface: not opaque, dims what lies beyond it. Triangles counter-clockwise seen from
  // outside the water (TriangleMesh's convention): a crossing enters the water when the ray runs
  // against the outward normal, so duplicate hits on shared edges do no harm.
  const TriangleMesh* water = nullptr;
  const TriangleMesh* solids = nullptr;  // opaque: the first hit ends the ray
};

// Per pixel: C_p = (1 - L) C_d + L C_b (see composite.h). Rows top to bottom.
struct VolumeImage {
  int width = 0, height = 0;
  std::vector<float> transmittance;  // L in [0, 1]; 1 where nothing diffuse is seen
  std::vector<Vec3f> color;          // C_d, linear; 0 where L == 1
  // With VolumeSettings::split_types (else empty), per type: its premultiplied colour and opacity,
  // which sum over the types to (1 - L) C_d and 1 - L (absorption.h's PixelAverage).
  std::array<std::vector<Vec3f>, kDiffuseTypeCount> type_premultiplied;
  std::array<std::vector<float>, kDiffuseTypeCount> type_opacity;

  size_t pixel_count() const { return size_t(width) * size_t(height); }
};

struct VolumeStats {
  bool skipped = false;        // no drawn diffuse particle: nothing was built or traced
  size_t spheres = 0;          // drawn diffuse particles
  size_t rays = 0;             // eye rays (pixels x samples)
  size_t intervals = 0;        // exact: ray/sphere chords found; march: samples taken
  double build_seconds = 0.0;  // acceleration structures (Embree scenes, bins, grids)
  double trace_seconds = 0.0;  // everything per ray
};

}  // namespace spume

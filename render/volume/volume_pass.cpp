#include "render/volume/volume_pass.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <optional>

#include <tbb/enumerable_thread_specific.h>

#include "render/keys/render_keys.h"
#include "render/volume/absorption.h"
#include "render/volume/bin_trace.h"
#include "render/volume/drawn_bounds.h"
#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/core/stopwatch.h"
#include "render/volume/embree_scene.h"
#include "render/volume/point_grid.h"
#include "render/volume/screen_bins.h"
#include "render/volume/swept_trace.h"
#include "render/surface/triangle_mesh.h"
#include "render/volume/tile_rays.h"

namespace spume {
namespace {

constexpr int kTile = ScreenBins::kTile, kBin = ScreenBins::kBin;

bool finite3(const Vec3f& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

void validate(DiffuseView frame, const Camera& camera, const VolumeSettings& s) {
  for (int k = 0; k < kDiffuseTypeCount; ++k) {
    const DiffuseLook& l = s.look[size_t(k)];
    const char* name = to_string(DiffuseType(k));
    if (!std::isfinite(l.radius) || l.radius < 0.0f) fail("volume pass: ", name, " radius ", l.radius, " m: must be >= 0 (0 = not drawn)");
    if (!finite3(l.color)) fail("volume pass: ", name, " colour is not finite");
  }
  if (!std::isfinite(s.alpha) || s.alpha < 0.0f) fail("volume pass: alpha ", s.alpha, " 1/m: must be >= 0");
  if (!finite3(s.water_sigma) || s.water_sigma.minCoeff() < 0.0f) fail("volume pass: water sigma must be >= 0 per channel (1/m)");
  if (const std::string why = out_of_range(keys::render::spp, s.samples_per_pixel); !why.empty())
    fail("volume pass: samples per pixel (", keys::render::spp.path, "): ", why);
  if (!std::isfinite(s.march_step)) fail("volume pass: march step is not finite");
  if (camera.width <= 0 || camera.height <= 0) fail("volume pass: image size ", camera.width, "x", camera.height, " is empty");
  if (frame.types.size() != frame.positions.size())
    fail("volume pass: frame ", frame.index, " has ", frame.positions.size(), " positions but ", frame.types.size(), " types");
}

// Everything the tile workers share, read-only.
struct Pass {
  const DiffuseView* frame;
  const Camera* camera;
  const VolumeSettings* settings;
  VolumeShading shading;
  std::array<double, kDiffuseTypeCount> r2{};
  TileRayParams ray_params;
  const ScreenBins* bins = nullptr;
  const SweptBins* swept = nullptr;  // motion blur
  DiffuseMotion motion;
  const SphereHitScene* hits = nullptr;
  const std::array<PointGrid, kDiffuseTypeCount>* grids = nullptr;
  double dx = 0.0;
};

struct Scratch {
  TileRays tile;
  BinScratch bin;
  std::vector<SphereHitScene::Hit> hits;
  std::vector<Interval> intervals;
  SweptTraceScratch swept;
};

size_t exact_embree(const Pass& pass, Scratch& s, std::vector<RaySample>& out, std::vector<RayTypes>* types) {
  const TileRays& t = s.tile;
  const Vec3d o = pass.camera->position.cast<double>();
  size_t found = 0;
  for (size_t i = 0; i < t.rays.size(); ++i) {
    const TileRay& r = t.rays[i];
    if (r.misses()) continue;
    // Slightly wider than [t_in, t_out]: Embree's float t's only nominate spheres; chords are exact.
    const float t_near = float(std::max(0.0, r.t_in * (1.0 - 1e-5) - 1e-6));
    const float t_far = std::isfinite(r.t_out) ? float(r.t_out * (1.0 + 1e-5) + 1e-6) : INFINITY;
    pass.hits->collect(pass.camera->position, r.direction_f, t_near, t_far, s.hits);
    s.intervals.clear();
    for (const SphereHitScene::Hit& h : s.hits) {
      const Vec3d oc = h.centre.cast<double>() - o;
      double t0, t1;
      if (!ray_sphere_chord(oc, oc.squaredNorm(), r.direction, pass.r2[h.type], t0, t1)) continue;
      t0 = std::max(t0, r.t_in), t1 = std::min(t1, r.t_out);
      if (t1 > t0) s.intervals.push_back({float(t0 - r.t_in), float(t1 - r.t_in), h.type});
    }
    found += s.intervals.size();
    std::sort(s.intervals.begin(), s.intervals.end(), [](const Interval& a, const Interval& b) { return interval_before(a, b); });
    out[i] = absorb_intervals(s.intervals.data(), s.intervals.size(), pass.shading, water_of(t, r),
                              types ? &(*types)[i] : nullptr);
  }
  return found;
}

size_t march(const Pass& pass, Scratch& s, std::vector<RaySample>& out, std::vector<RayTypes>* types) {
  const TileRays& t = s.tile;
  const Vec3d o = pass.camera->position.cast<double>();
  size_t samples = 0;
  for (size_t i = 0; i < t.rays.size(); ++i) {
    const TileRay& r = t.rays[i];
    if (r.misses()) continue;
    MarchAccumulator acc(pass.shading, water_of(t, r), pass.dx);
    const size_t steps = size_t(std::floor((r.t_out - r.t_in) / pass.dx));  // s of Eq. 9
    for (size_t j = 0; j <= steps; ++j) {
      const double tj = r.t_in + double(j) * pass.dx;
      const Vec3d x = o + tj * r.direction;
      unsigned mask = 0;
      for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k)
        if ((*pass.grids)[k].covers(x)) mask |= 1u << k;
      acc.add(mask, tj - r.t_in);
    }
    samples += steps + 1;
    out[i] = acc.finish(types ? &(*types)[i] : nullptr);
  }
  return samples;
}

}  // namespace

bool volume_pass_needed(DiffuseView frame, const VolumeSettings& settings) {
  const auto counts = frame.count_by_type();
  for (int k = 0; k < kDiffuseTypeCount; ++k)
    if (settings.drawn(DiffuseType(k)) && counts[size_t(k)] > 0) return true;
  return false;
}

double march_step(const VolumeSettings& settings) {
  if (settings.march_step > 0.0f) return settings.march_step;
  float r = INFINITY;
  for (const DiffuseLook& l : settings.look)
    if (l.radius > 0.0f) r = std::min(r, l.radius);
  return std::isfinite(r) ? 0.5 * double(r) : 0.0;
}

VolumeImage render_volume(DiffuseView frame, const Camera& camera, const VolumeSettings& settings,
                          const VolumeSurfaces& surfaces, VolumeStats* stats, std::span<const Vec3f> velocities) {
  validate(frame, camera, settings);
  if (settings.blurs() && settings.integrator != VolumeIntegrator::Exact)
    fail("volume pass: motion blur (shutter ", settings.shutter, ") needs the exact integrator");
  if (settings.blurs() && velocities.size() != frame.size())
    fail("volume pass: motion blur needs a velocity per particle; frame ", frame.index, " has ", frame.size(),
         " particles and ", velocities.size(), " velocities");
  VolumeStats st;
  VolumeImage img;
  img.width = camera.width, img.height = camera.height;
  img.transmittance.assign(img.pixel_count(), 1.0f);
  img.color.assign(img.pixel_count(), Vec3f::Zero());
  if (settings.split_types)
    for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k) {
      img.type_premultiplied[k].assign(img.pixel_count(), Vec3f::Zero());
      img.type_opacity[k].assign(img.pixel_count(), 0.0f);
    }

  std::array<float, kDiffuseTypeCount> radius{};
  for (int k = 0; k < kDiffuseTypeCount; ++k) radius[size_t(k)] = settings.look[size_t(k)].radius;
  const Stopwatch build_start;
  Aabb bounds = drawn_bounds(frame, radius, st.spheres);
  if (st.spheres == 0) {
    st.skipped = true;
    if (stats) *stats = st;
    return img;
  }

  Pass pass;
  const int spp = settings.samples_per_pixel;
  std::unique_ptr<SweptBins> swept;
  if (settings.blurs()) {  // the rays' box must hold every path, not the spheres at the frame's time
    const double half = 0.5 * double(settings.shutter) * settings.frame_seconds;
    pass.motion = {velocities, -half, half, settings.gravity.cast<double>()};
    swept = std::make_unique<SweptBins>(frame, pass.motion, radius,
                                        SphereProjector(camera, spp == 1 ? 0.5 : 0.0, spp == 1 ? 0.5 : 1.0),
                                        camera.width, camera.height);
    bounds = swept->bounds();
    pass.swept = swept.get();
  }
  pass.frame = &frame, pass.camera = &camera, pass.settings = &settings;
  pass.shading.alpha = settings.alpha;
  pass.shading.water_sigma = settings.water_sigma.cast<double>();
  for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k) {
    pass.shading.color[k] = settings.look[k].color.cast<double>();
    pass.r2[k] = double(radius[k]) * double(radius[k]);
  }
  std::optional<SurfaceScene> surface_scene;
  if ((surfaces.water && !surfaces.water->empty()) || (surfaces.solids && !surfaces.solids->empty()))
    surface_scene.emplace(surfaces);
  // Bounds a hair larger than the spheres: float centres and radii, double rays.
  const Vec3d pad = Vec3d::Constant(1e-6 * (1.0 + (bounds.max - bounds.min).cast<double>().norm()));
  pass.ray_params = {&camera, bounds.min.cast<double>() - pad, bounds.max.cast<double>() + pad,
                     surface_scene ? &*surface_scene : nullptr, settings.seed, frame.index, spp};
  std::unique_ptr<ScreenBins> bins;
  std::unique_ptr<SphereHitScene> hit_scene;
  std::unique_ptr<std::array<PointGrid, kDiffuseTypeCount>> grids;
  if (pass.swept) {  // built above
  } else if (settings.integrator == VolumeIntegrator::March) {
    pass.dx = march_step(settings);
    // Guard against a step that would take practically forever (e.g. a typo in the scene file).
    const double diagonal = (bounds.max - bounds.min).cast<double>().norm();
    if (!(pass.dx > 0.0) || diagonal / pass.dx > 1e7)
      fail("volume pass: march step ", pass.dx, " m is too small for diffuse bounds ", diagonal, " m across (at most 1e7 steps per ray)");
    grids = std::make_unique<std::array<PointGrid, kDiffuseTypeCount>>();
    for (int k = 0; k < kDiffuseTypeCount; ++k)
      if (radius[size_t(k)] > 0.0f) (*grids)[size_t(k)] = PointGrid(frame, DiffuseType(k), radius[size_t(k)]);
    pass.grids = grids.get();
  } else if (settings.exact_method == ExactMethod::ScreenBins) {
    const SphereProjector projector(camera, spp == 1 ? 0.5 : 0.0, spp == 1 ? 0.5 : 1.0);
    bins = std::make_unique<ScreenBins>(frame, radius, projector, camera.width, camera.height);
    pass.bins = bins.get();
  } else {
    hit_scene = std::make_unique<SphereHitScene>(frame, radius);
    pass.hits = hit_scene.get();
  }
  st.build_seconds = build_start.seconds();

  const Stopwatch trace_start;
  // Bins of 2x2 tiles (ScreenBins::kBin), each tile's pixels written by one task only.
  const int bins_x = (camera.width + kBin - 1) / kBin, bins_y = (camera.height + kBin - 1) / kBin;
  tbb::enumerable_thread_specific<Scratch> scratch;
  std::atomic<size_t> found{0};
  parallel_for(size_t(bins_x) * size_t(bins_y), 1, [&](size_t b, size_t e) {
    Scratch& s = scratch.local();
    std::vector<RaySample> samples;
    std::vector<RayTypes> split;  // with settings.split_types
    std::vector<RayTypes>* types = settings.split_types ? &split : nullptr;
    for (size_t bin = b; bin < e; ++bin) {
      const int bx = int(bin % size_t(bins_x)) * kBin, by = int(bin / size_t(bins_x)) * kBin;
      if (pass.bins) order_bin(pass.bins->begin(bin), pass.bins->end(bin), *pass.camera, s.bin);
      for (int oy = 0; oy < kBin && by + oy < camera.height; oy += kTile)
        for (int ox = 0; ox < kBin && bx + ox < camera.width; ox += kTile) {
          const int x0 = bx + ox, y0 = by + oy;
          const int w = std::min(kTile, camera.width - x0), h = std::min(kTile, camera.height - y0);
          // With screen bins, only rays some sphere may touch are traced against the surfaces (at the
          // lighthouse's 15M, 30% of those that reach the diffuse bounds).
          const uint8_t* wanted = pass.swept ? swept_candidates(*pass.swept, x0, y0, w, h, spp, s.swept).data()
                                  : pass.bins ? count_tile_candidates(ox, oy, w, h, spp, s.bin).data()
                                              : nullptr;
          make_tile_rays(pass.ray_params, x0, y0, w, h, s.tile, wanted);
          samples.assign(s.tile.rays.size(), RaySample{});
          if (types) split.assign(s.tile.rays.size(), RayTypes{});
          size_t n = 0;
          if (pass.swept) {
            n = trace_swept_tile(s.tile, *pass.swept, *pass.frame, pass.motion, pass.camera->position.cast<double>(),
                                 pass.r2, pass.shading, s.swept, samples, types);
          } else if (pass.grids) {
            n = march(pass, s, samples, types);
          } else if (pass.bins) {
            n = trace_bin_tile(s.tile, ox, oy, pass.camera->position.cast<double>(), pass.r2, pass.shading, s.bin, samples,
                               types);
          } else {
            n = exact_embree(pass, s, samples, types);
          }
          found += n;
          for (int ly = 0; ly < h; ++ly)
            for (int lx = 0; lx < w; ++lx) {
              PixelAverage avg(settings.split_types);
              for (int k = 0; k < spp; ++k) {
                const size_t ri = (size_t(ly) * size_t(w) + size_t(lx)) * size_t(spp) + size_t(k);
                avg.add(samples[ri], types ? &split[ri] : nullptr);
              }
              const size_t p = size_t(y0 + ly) * size_t(camera.width) + size_t(x0 + lx);
              avg.finish(img.transmittance[p], img.color[p]);
              if (settings.split_types)
                for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k)
                  avg.finish_type(k, img.type_premultiplied[k][p], img.type_opacity[k][p]);
            }
        }
    }
  });
  st.trace_seconds = trace_start.seconds();
  st.rays = img.pixel_count() * size_t(spp);
  st.intervals = found;
  if (stats) *stats = st;
  return img;
}

}  // namespace spume

#include "render/volume/volume_pass.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <optional>

#include <emmintrin.h>
#include <tbb/enumerable_thread_specific.h>

#include "render/keys/render_keys.h"
#include "render/volume/absorption.h"
#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/core/stopwatch.h"
#include "render/volume/embree_scene.h"
#include "render/volume/point_grid.h"
#include "render/volume/screen_bins.h"
#include "render/surface/triangle_mesh.h"
#include "render/volume/tile_rays.h"

namespace spume {
namespace {

constexpr int kTile = ScreenBins::kTile, kBin = ScreenBins::kBin;

bool finite3(const Vec3f& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

void validate(const DiffuseFrame& frame, const Camera& camera, const VolumeSettings& s) {
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
  const DiffuseFrame* frame;
  const Camera* camera;
  const VolumeSettings* settings;
  VolumeShading shading;
  std::array<double, kDiffuseTypeCount> r2{};
  TileRayParams ray_params;
  const ScreenBins* bins = nullptr;
  const SphereHitScene* hits = nullptr;
  const std::array<PointGrid, kDiffuseTypeCount>* grids = nullptr;
  double dx = 0.0;
};

struct Scratch {
  TileRays tile;
  std::vector<BinnedSphere> bin_sorted;  // the bin's spheres, near to far
  std::vector<BinnedSphere> sorted;      // those of the current tile, rectangles tile-relative
  std::vector<float> depth;
  std::vector<uint32_t> bucket, bucket_of;
  std::vector<uint32_t> ray_start, ray_end;  // per ray of the tile: its chords in `chords`
  std::vector<Interval> chords;
  std::vector<double> ray_soa;  // ray_columns
  std::vector<SphereHitScene::Hit> hits;
  std::vector<Interval> intervals;
};

WaterView water_of(const TileRays& t, const TileRay& r) {
  return {t.water.data() + r.water_begin, size_t(r.water_end - r.water_begin)};
}

// The bin's spheres in near-to-far order (buckets about a radius deep; particle order within), so
// each ray's chords arrive almost sorted by entry and sort_intervals is about one pass. The order
// only affects speed: chords are sorted by value before they are summed.
void depth_order(const BinnedSphere* b, const BinnedSphere* e, const Camera& cam, Scratch& s) {
  const size_t n = size_t(e - b);
  Vec3f right, up, back;
  cam.basis(right, up, back);
  const Vec3f o = cam.position;
  // -z of the sphere's centre along the view axis, once per sphere (here and for its bucket).
  s.depth.resize(n);
  s.bucket_of.resize(n);
  float* z = s.depth.data();
  float zmin = INFINITY, zmax = -INFINITY;
  for (size_t i = 0; i < n; ++i) {
    z[i] = -(b[i].centre() - o).dot(back);
    zmin = std::min(zmin, z[i]), zmax = std::max(zmax, z[i]);
  }
  const size_t buckets = std::clamp<size_t>(n, 1, 8192);
  const float scale = zmax > zmin ? float(buckets) / (zmax - zmin) : 0.0f;
  s.bucket.assign(buckets + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t k = uint32_t(std::min(buckets - 1, size_t((z[i] - zmin) * scale)));
    s.bucket_of[i] = k;
    ++s.bucket[k + 1];
  }
  for (size_t i = 0; i < buckets; ++i) s.bucket[i + 1] += s.bucket[i];
  s.bin_sorted.resize(n);
  for (size_t i = 0; i < n; ++i) s.bin_sorted[s.bucket[s.bucket_of[i]]++] = b[i];
}

// The bin's spheres seen in the tile at (ox, oy) of the bin, w x h pixels, in the same order, with
// their rectangles clipped to the tile and made relative to it.
void tile_spheres(Scratch& s, int ox, int oy, int w, int h) {
  s.sorted.resize(s.bin_sorted.size());
  size_t k = 0;
  for (const BinnedSphere& sp : s.bin_sorted) {
    const int x0 = std::max(sp.x0(), ox), x1 = std::min(sp.x1(), ox + w - 1);
    const int y0 = std::max(sp.y0(), oy), y1 = std::min(sp.y1(), oy + h - 1);
    s.sorted[k] = BinnedSphere::make(sp.centre(), uint32_t(x0 - ox), uint32_t(x1 - ox), uint32_t(y0 - oy), uint32_t(y1 - oy), sp.type());
    k += x0 <= x1 && y0 <= y1 ? 1 : 0;
  }
  s.sorted.resize(k);
}

// Per ray of the tile, room for one chord per candidate sphere: the rectangles summed by a 2D
// difference array, so the chord loop below stores without a size check and without a branch.
void reserve_chords(const TileRays& t, Scratch& s) {
  const size_t w = size_t(t.w), h = size_t(t.h), spp = size_t(t.spp);
  std::array<uint32_t, (kTile + 1) * (kTile + 1)> diff{};
  for (const BinnedSphere& sp : s.sorted) {
    const size_t x0 = size_t(sp.x0()), x1 = size_t(sp.x1()) + 1, y0 = size_t(sp.y0()), y1 = size_t(sp.y1()) + 1;
    ++diff[y0 * (kTile + 1) + x0], ++diff[y1 * (kTile + 1) + x1];
    --diff[y0 * (kTile + 1) + x1], --diff[y1 * (kTile + 1) + x0];
  }
  s.ray_start.resize(w * h * spp + 1);
  s.ray_end.resize(w * h * spp);
  std::array<uint32_t, kTile> column{};  // running sums down each column
  uint32_t total = 0;
  for (size_t y = 0; y < h; ++y) {
    uint32_t row = 0;
    for (size_t x = 0; x < w; ++x) {
      row += diff[y * (kTile + 1) + x];
      column[x] += row;
      for (size_t k = 0; k < spp; ++k) {
        const size_t ri = (y * w + x) * spp + k;
        s.ray_start[ri] = s.ray_end[ri] = total;
        total += column[x];
      }
    }
  }
  s.ray_start[w * h * spp] = total;
  if (s.chords.size() < total) s.chords.resize(total);
}

// The tile's rays as arrays of doubles (direction x, y, z, t_in, t_out), for the chord loop.
void ray_columns(const TileRays& t, Scratch& s) {
  const size_t n = t.rays.size();
  s.ray_soa.resize(5 * n);
  double* c = s.ray_soa.data();
  for (size_t i = 0; i < n; ++i) {
    const TileRay& r = t.rays[i];
    c[i] = r.direction.x(), c[n + i] = r.direction.y(), c[2 * n + i] = r.direction.z();
    c[3 * n + i] = r.t_in, c[4 * n + i] = r.t_out;
  }
}

// Every candidate chord of the tile's spheres (s.sorted) into its ray's room (reserve_chords):
// ray_sphere_chord and the clip to [t_in, t_out] for two rays at once (SSE2, part of x86-64),
// without a branch: a miss (or a ray that misses the bounds, t_in > t_out) leaves t1 <= t0, and
// the slot is reused by the ray's next chord. The same double operations in the same order as the
// scalar code (Eigen's dot is (x + y) + z; std::max(a, b) is _mm_max_pd(b, a)), so the same bits.
// The square root was the loop's bottleneck; two lanes halve its count.
void tile_chords(const Pass& pass, Scratch& s) {
  const TileRays& t = s.tile;
  const size_t n = t.rays.size(), spp = size_t(t.spp), w = size_t(t.w);
  ray_columns(t, s);
  const double *dx = s.ray_soa.data(), *dy = dx + n, *dz = dx + 2 * n, *tin = dx + 3 * n, *tout = dx + 4 * n;
  const Vec3d o = pass.camera->position.cast<double>();
  Interval* chords = s.chords.data();
  uint32_t* end = s.ray_end.data();
  const __m128d zero = _mm_setzero_pd();
  for (const BinnedSphere& sp : s.sorted) {
    const Vec3d oc = sp.centre().cast<double>() - o;
    const double oc2 = oc.squaredNorm(), r2 = pass.r2[sp.type()];
    const uint32_t type = sp.type();
    const __m128d ocx = _mm_set1_pd(oc.x()), ocy = _mm_set1_pd(oc.y()), ocz = _mm_set1_pd(oc.z());
    const __m128d oc2v = _mm_set1_pd(oc2), r2v = _mm_set1_pd(r2);
    const size_t x0 = size_t(sp.x0()) * spp, x1 = (size_t(sp.x1()) + 1) * spp;
    for (size_t ly = size_t(sp.y0()), y1 = size_t(sp.y1()); ly <= y1; ++ly) {
      const size_t row = ly * w * spp, e = row + x1;
      size_t ri = row + x0;
      for (; ri + 2 <= e; ri += 2) {
        const __m128d tc = _mm_add_pd(_mm_add_pd(_mm_mul_pd(ocx, _mm_loadu_pd(dx + ri)), _mm_mul_pd(ocy, _mm_loadu_pd(dy + ri))),
                                      _mm_mul_pd(ocz, _mm_loadu_pd(dz + ri)));
        const __m128d b2 = _mm_sub_pd(oc2v, _mm_mul_pd(tc, tc));
        const __m128d hw = _mm_sqrt_pd(_mm_max_pd(zero, _mm_sub_pd(r2v, b2)));
        const __m128d a = _mm_loadu_pd(tin + ri), b = _mm_loadu_pd(tout + ri);
        const __m128d t0 = _mm_max_pd(a, _mm_sub_pd(tc, hw)), t1 = _mm_min_pd(b, _mm_add_pd(tc, hw));
        const int hit = _mm_movemask_pd(_mm_cmpgt_pd(t1, t0));
        alignas(16) float f[4];
        _mm_store_ps(f, _mm_movelh_ps(_mm_cvtpd_ps(_mm_sub_pd(t0, a)), _mm_cvtpd_ps(_mm_sub_pd(t1, a))));
        chords[end[ri]] = {f[0], f[2], type};
        end[ri] += uint32_t(hit & 1);
        chords[end[ri + 1]] = {f[1], f[3], type};
        end[ri + 1] += uint32_t(hit >> 1);
      }
      if (ri < e) {  // an odd one at the row's end
        const double tc = (oc.x() * dx[ri] + oc.y() * dy[ri]) + oc.z() * dz[ri], b2 = oc2 - tc * tc;
        const double hw = std::sqrt(std::max(r2 - b2, 0.0));
        const double t0 = std::max(tc - hw, tin[ri]), t1 = std::min(tc + hw, tout[ri]);
        chords[end[ri]] = {float(t0 - tin[ri]), float(t1 - tin[ri]), type};
        end[ri] += t1 > t0 ? 1u : 0u;
      }
    }
  }
}

// The tile's transmittance and colour from s.sorted (tile_spheres).
size_t exact_screen_bins(const Pass& pass, Scratch& s, std::vector<RaySample>& out) {
  const TileRays& t = s.tile;
  reserve_chords(t, s);
  tile_chords(pass, s);
  size_t found = 0;
  for (size_t i = 0; i < t.rays.size(); ++i) {
    Interval* l = s.chords.data() + s.ray_start[i];
    const size_t n = s.ray_end[i] - s.ray_start[i];
    found += n;
    sort_intervals(l, n);
    out[i] = absorb_intervals(l, n, pass.shading, water_of(t, t.rays[i]));
  }
  return found;
}

size_t exact_embree(const Pass& pass, Scratch& s, std::vector<RaySample>& out) {
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
    out[i] = absorb_intervals(s.intervals.data(), s.intervals.size(), pass.shading, water_of(t, r));
  }
  return found;
}

size_t march(const Pass& pass, Scratch& s, std::vector<RaySample>& out) {
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
    out[i] = acc.finish();
  }
  return samples;
}

// Box around every drawn sphere; counts them. Fixed chunks, exact min/max: deterministic.
Aabb drawn_bounds(const DiffuseFrame& frame, const std::array<float, kDiffuseTypeCount>& radius, size_t& count) {
  const size_t n = frame.size(), chunks = std::clamp<size_t>(n / 65536, 1, 64);
  std::vector<Aabb> box(chunks);
  std::vector<size_t> drawn(chunks, 0), bad(chunks, SIZE_MAX);
  parallel_for(chunks, 1, [&](size_t c0, size_t c1) {
    for (size_t c = c0; c < c1; ++c)
      for (size_t i = c * n / chunks; i < (c + 1) * n / chunks; ++i) {
        const size_t type = size_t(frame.types[i]);
        if (type >= size_t(kDiffuseTypeCount)) {
          bad[c] = std::min(bad[c], i);
          continue;
        }
        const float r = radius[type];
        if (!(r > 0.0f)) continue;
        const Vec3f& p = frame.positions[i];
        if (!finite3(p)) {
          bad[c] = std::min(bad[c], i);
          continue;
        }
        box[c].min = box[c].min.cwiseMin(p - Vec3f::Constant(r));
        box[c].max = box[c].max.cwiseMax(p + Vec3f::Constant(r));
        ++drawn[c];
      }
  });
  Aabb all;
  count = 0;
  for (size_t c = 0; c < chunks; ++c) {
    if (bad[c] != SIZE_MAX)
      fail("volume pass: frame ", frame.index, " particle ", bad[c], " has a non-finite position or a type outside 0..2");
    if (drawn[c]) all.extend(box[c]);
    count += drawn[c];
  }
  return all;
}

}  // namespace

bool volume_pass_needed(const DiffuseFrame& frame, const VolumeSettings& settings) {
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

VolumeImage render_volume(const DiffuseFrame& frame, const Camera& camera, const VolumeSettings& settings,
                          const VolumeSurfaces& surfaces, VolumeStats* stats) {
  validate(frame, camera, settings);
  VolumeStats st;
  VolumeImage img;
  img.width = camera.width, img.height = camera.height;
  img.transmittance.assign(img.pixel_count(), 1.0f);
  img.color.assign(img.pixel_count(), Vec3f::Zero());

  std::array<float, kDiffuseTypeCount> radius{};
  for (int k = 0; k < kDiffuseTypeCount; ++k) radius[size_t(k)] = settings.look[size_t(k)].radius;
  const Stopwatch build_start;
  const Aabb bounds = drawn_bounds(frame, radius, st.spheres);
  if (st.spheres == 0) {
    st.skipped = true;
    if (stats) *stats = st;
    return img;
  }

  Pass pass;
  pass.frame = &frame, pass.camera = &camera, pass.settings = &settings;
  pass.shading.alpha = settings.alpha;
  pass.shading.water_sigma = settings.water_sigma.cast<double>();
  for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k) {
    pass.shading.color[k] = settings.look[k].color.cast<double>();
    pass.r2[k] = double(radius[k]) * double(radius[k]);
  }
  const int spp = settings.samples_per_pixel;
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
  if (settings.integrator == VolumeIntegrator::March) {
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
    for (size_t bin = b; bin < e; ++bin) {
      const int bx = int(bin % size_t(bins_x)) * kBin, by = int(bin / size_t(bins_x)) * kBin;
      if (pass.bins) depth_order(pass.bins->begin(bin), pass.bins->end(bin), *pass.camera, s);
      for (int oy = 0; oy < kBin && by + oy < camera.height; oy += kTile)
        for (int ox = 0; ox < kBin && bx + ox < camera.width; ox += kTile) {
          const int x0 = bx + ox, y0 = by + oy;
          const int w = std::min(kTile, camera.width - x0), h = std::min(kTile, camera.height - y0);
          make_tile_rays(pass.ray_params, x0, y0, w, h, s.tile);
          samples.assign(s.tile.rays.size(), RaySample{});
          size_t n = 0;
          if (pass.grids) {
            n = march(pass, s, samples);
          } else if (pass.bins) {
            tile_spheres(s, ox, oy, w, h);
            n = exact_screen_bins(pass, s, samples);
          } else {
            n = exact_embree(pass, s, samples);
          }
          found += n;
          for (int ly = 0; ly < h; ++ly)
            for (int lx = 0; lx < w; ++lx) {
              PixelAverage avg;
              for (int k = 0; k < spp; ++k) avg.add(samples[(size_t(ly) * size_t(w) + size_t(lx)) * size_t(spp) + size_t(k)]);
              const size_t p = size_t(y0 + ly) * size_t(camera.width) + size_t(x0 + lx);
              avg.finish(img.transmittance[p], img.color[p]);
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

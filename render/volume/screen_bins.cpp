#include "render/volume/screen_bins.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume {

SphereProjector::SphereProjector(const Camera& camera, double jitter_lo, double jitter_hi)
    : width_(camera.width), height_(camera.height) {
  Vec3f back;
  camera.basis(right_, up_, back);
  origin_ = camera.position, forward_ = -back;
  tan_y_ = float(std::tan(0.5 * double(camera.fov_y_degrees) * std::numbers::pi / 180.0));
  tan_x_ = tan_y_ * float(camera.width) / float(camera.height);
  cull_x_ = 1.0f / std::sqrt(1.0f + tan_x_ * tan_x_);
  cull_y_ = 1.0f / std::sqrt(1.0f + tan_y_ * tan_y_);
  scale_x_ = 0.5f * float(width_) / tan_x_, scale_y_ = 0.5f * float(height_) / tan_y_;
  // 0.01 pixel covers float rounding here and in Camera::ray (~1e-7 relative, 1e-4 pixel at 1080p).
  const float m = 0.01f + 1e-6f * float(std::max(width_, height_));
  lo_margin_ = m + float(jitter_hi), hi_margin_ = m - float(jitter_lo);
}

bool SphereProjector::pixel_rect(const Vec3f& centre, float radius, int& x0, int& y0, int& x1, int& y1) const {
  const Vec3f v = centre - origin_;
  const float X = v.dot(right_), Y = v.dot(up_), Z = v.dot(forward_);
  // Slightly inflated: position rounding (~1e-7 |v|) must not cut off a sphere's edge.
  const float r = radius * (1.0f + 1e-5f) + 1e-6f * (std::abs(X) + std::abs(Y) + std::abs(Z));
  if (Z < -r) return false;
  // Outside one of the four side planes of the frustum by more than r.
  if ((std::abs(X) - tan_x_ * Z) * cull_x_ > r || (std::abs(Y) - tan_y_ * Z) * cull_y_ > r) return false;
  if (Z <= r) {  // reaches the camera plane: its projection is unbounded
    x0 = 0, y0 = 0, x1 = width_ - 1, y1 = height_ - 1;
    return true;
  }
  // Image-plane extent at unit depth from the two planes through the camera tangent to the sphere
  // that contain its up axis (for x) or right axis (for y):
  // s = (X Z -+ r sqrt(X^2 + Z^2 - r^2)) / (Z^2 - r^2).
  const float den = Z * Z - r * r, inv = 1.0f / den;
  const float rx = r * std::sqrt(X * X + den), ry = r * std::sqrt(Y * Y + den);
  // Camera::ray: sx = (2 px / W - 1) tan_x, sy = (1 - 2 py / H) tan_y.
  const float cx = 0.5f * float(width_), cy = 0.5f * float(height_);
  const float px_lo = cx + scale_x_ * (X * Z - rx) * inv, px_hi = cx + scale_x_ * (X * Z + rx) * inv;
  const float py_lo = cy - scale_y_ * (Y * Z + ry) * inv, py_hi = cy - scale_y_ * (Y * Z - ry) * inv;
  // Pixel x is a candidate when a sample x + j, j in [jitter_lo, jitter_hi], lies in [px_lo, px_hi].
  // Clamped to just outside the image first, so the integer conversions below cannot overflow.
  const float w = float(width_), h = float(height_);
  const float ax0 = std::clamp(px_lo - lo_margin_, -2.0f, w + 2.0f), ax1 = std::clamp(px_hi + hi_margin_, -2.0f, w + 2.0f);
  const float ay0 = std::clamp(py_lo - lo_margin_, -2.0f, h + 2.0f), ay1 = std::clamp(py_hi + hi_margin_, -2.0f, h + 2.0f);
  if (!(ax0 <= ax1 && ay0 <= ay1)) return false;  // also rejects NaN
  // floor/ceil by truncation: x86-64 without SSE4.1 has no rounding instruction and the libm calls
  // were a visible share of binning 15M spheres.
  auto floor_i = [](float a) { const int i = int(a); return i - (a < float(i)); };
  auto ceil_i = [](float a) { const int i = int(a); return i + (a > float(i)); };
  x0 = std::max(ceil_i(ax0), 0), x1 = std::min(floor_i(ax1), width_ - 1);
  y0 = std::max(ceil_i(ay0), 0), y1 = std::min(floor_i(ay1), height_ - 1);
  if (x0 > x1 || y0 > y1) return false;
  return true;
}

namespace {
const bool kHasAvx2 = __builtin_cpu_supports("avx2");
}  // namespace

void SphereProjector::pixel_rects(const Vec3f* centres, const float* radii, size_t n, Rects& out) const {
  if (kHasAvx2)
    pixel_rects_avx2(centres, radii, n, out);
  else
    pixel_rects_loop(centres, radii, n, out);
}

__attribute__((target("avx2"))) void SphereProjector::pixel_rects_avx2(const Vec3f* centres, const float* radii, size_t n,
                                                                       Rects& out) const {
  pixel_rects_loop(centres, radii, n, out);
}

// Inlined into both callers, so each is vectorised for its own instruction set.
__attribute__((always_inline)) inline void SphereProjector::pixel_rects_loop(const Vec3f* centres, const float* radii, size_t n,
                                                                             Rects& out) const {
  // pixel_rect's expressions in its order, as selects instead of early returns.
  const float ox = origin_.x(), oy = origin_.y(), oz = origin_.z();
  const float cx = 0.5f * float(width_), cy = 0.5f * float(height_), w = float(width_), h = float(height_);
  float px[kBatch], py[kBatch], pz[kBatch];
  for (size_t i = 0; i < n; ++i) px[i] = centres[i].x(), py[i] = centres[i].y(), pz[i] = centres[i].z();
  for (size_t i = 0; i < n; ++i) {
    const float vx = px[i] - ox, vy = py[i] - oy, vz = pz[i] - oz;
    const float X = vx * right_.x() + vy * right_.y() + vz * right_.z();
    const float Y = vx * up_.x() + vy * up_.y() + vz * up_.z();
    const float Z = vx * forward_.x() + vy * forward_.y() + vz * forward_.z();
    const float radius = radii[i];
    const float aX = std::abs(X), aY = std::abs(Y);
    const float r = radius * (1.0f + 1e-5f) + 1e-6f * (aX + aY + std::abs(Z));
    const bool seen = (radius > 0.0f) & !(Z < -r) & !((aX - tan_x_ * Z) * cull_x_ > r) & !((aY - tan_y_ * Z) * cull_y_ > r);
    const bool whole = Z <= r;
    const float den = Z * Z - r * r, inv = 1.0f / den;
    const float rx = r * std::sqrt(std::max(X * X + den, 0.0f)), ry = r * std::sqrt(std::max(Y * Y + den, 0.0f));
    const float px_lo = cx + scale_x_ * (X * Z - rx) * inv, px_hi = cx + scale_x_ * (X * Z + rx) * inv;
    const float py_lo = cy - scale_y_ * (Y * Z + ry) * inv, py_hi = cy - scale_y_ * (Y * Z - ry) * inv;
    const float ax0 = std::min(std::max(px_lo - lo_margin_, -2.0f), w + 2.0f), ax1 = std::min(std::max(px_hi + hi_margin_, -2.0f), w + 2.0f);
    const float ay0 = std::min(std::max(py_lo - lo_margin_, -2.0f), h + 2.0f), ay1 = std::min(std::max(py_hi + hi_margin_, -2.0f), h + 2.0f);
    const bool ordered = (ax0 <= ax1) & (ay0 <= ay1);
    const int ix0 = int(ax0), ix1 = int(ax1), iy0 = int(ay0), iy1 = int(ay1);
    const int x0 = std::max(ix0 + (ax0 > float(ix0) ? 1 : 0), 0), x1 = std::min(ix1 - (ax1 < float(ix1) ? 1 : 0), width_ - 1);
    const int y0 = std::max(iy0 + (ay0 > float(iy0) ? 1 : 0), 0), y1 = std::min(iy1 - (ay1 < float(iy1) ? 1 : 0), height_ - 1);
    const bool ok = seen & (whole | (ordered & (x0 <= x1) & (y0 <= y1)));
    out.x0[i] = !ok ? 1 : whole ? 0 : x0;
    out.x1[i] = !ok ? 0 : whole ? width_ - 1 : x1;
    out.y0[i] = !ok ? 0 : whole ? 0 : y0;
    out.y1[i] = !ok ? 0 : whole ? height_ - 1 : y1;
  }
}

namespace {
// The last freed entry array (see the constructor's comment in the header).
std::mutex spare_mutex;
HugePageArray<BinnedSphere> spare_entries;
}  // namespace

ScreenBins::~ScreenBins() {
  const std::lock_guard<std::mutex> lock(spare_mutex);
  if (entries_.capacity() > spare_entries.capacity()) std::swap(entries_, spare_entries);
}

ScreenBins::ScreenBins(DiffuseView frame, const std::array<float, kDiffuseTypeCount>& radius,
                       const SphereProjector& projector, int width, int height) {
  if (width <= 0 || height <= 0 || width > 65535 || height > 65535)
    fail("volume pass: image size ", width, "x", height, " outside 1..65535");
  bins_x_ = (width + kBin - 1) / kBin, bins_y_ = (height + kBin - 1) / kBin;
  const size_t bins = size_t(bins_x_) * size_t(bins_y_), n = frame.size();
  // Chunking depends on n only, so every bin list comes out in particle order for any thread count.
  const size_t chunks = std::clamp<size_t>(n / 16384, 1, 64);
  auto chunk_begin = [&](size_t c) { return c * n / chunks; };

  // Both passes project each batch of spheres (pixel_rects is cheap once vectorised): storing
  // the rectangles between them cost more, in page faults and memory traffic, than recomputing.
  auto project = [&](size_t b, size_t m, float* r, SphereProjector::Rects& q) {
    for (size_t j = 0; j < m; ++j) r[j] = radius[size_t(frame.types[b + j])];
    projector.pixel_rects(frame.positions.data() + b, r, m, q);
  };
  // Every sphere of chunk c that covers a pixel, in particle order, with its pixel rectangle: the
  // walk both passes make.
  auto each_visible = [&](size_t c, auto&& visit) {
    SphereProjector::Rects q;
    float r[SphereProjector::kBatch];
    for (size_t b = chunk_begin(c), e = chunk_begin(c + 1); b < e; b += SphereProjector::kBatch) {
      const size_t m = std::min(SphereProjector::kBatch, e - b);
      project(b, m, r, q);
      for (size_t j = 0; j < m; ++j)
        if (q.x0[j] <= q.x1[j]) visit(b + j, q.x0[j], q.y0[j], q.x1[j], q.y1[j]);  // else not drawn or not seen
    }
  };
  std::vector<uint32_t> count(chunks * bins, 0);  // per chunk, per bin
  parallel_for(chunks, 1, [&](size_t c0, size_t c1) {
    for (size_t c = c0; c < c1; ++c) {
      uint32_t* cnt = count.data() + c * bins;
      each_visible(c, [&](size_t, int x0, int y0, int x1, int y1) {
        for (int by = y0 / kBin; by <= y1 / kBin; ++by)
          for (int bx = x0 / kBin; bx <= x1 / kBin; ++bx) ++cnt[size_t(by) * size_t(bins_x_) + size_t(bx)];
      });
    }
  });

  // Offsets: bin-major, then chunk; `count` becomes each (chunk, bin)'s write cursor.
  bin_start_.assign(bins + 1, 0);
  size_t total = 0;
  for (size_t b = 0; b < bins; ++b) {
    bin_start_[b] = total;
    for (size_t c = 0; c < chunks; ++c) {
      const size_t k = count[c * bins + b];
      count[c * bins + b] = uint32_t(total - bin_start_[b]);
      total += k;
    }
  }
  bin_start_[bins] = total;
  {
    const std::lock_guard<std::mutex> lock(spare_mutex);
    std::swap(entries_, spare_entries);
  }
  entries_.allocate(total);

  parallel_for(chunks, 1, [&](size_t c0, size_t c1) {
    for (size_t c = c0; c < c1; ++c) {
      uint32_t* cursor = count.data() + c * bins;
      each_visible(c, [&](size_t i, int x0, int y0, int x1, int y1) {
        const Vec3f& p = frame.positions[i];
        const uint32_t type = uint32_t(frame.types[i]);
        for (int by = y0 / kBin; by <= y1 / kBin; ++by)
          for (int bx = x0 / kBin; bx <= x1 / kBin; ++bx) {
            const int ox = bx * kBin, oy = by * kBin;
            const uint32_t lx0 = uint32_t(std::max(x0, ox) - ox), lx1 = uint32_t(std::min(x1, ox + kBin - 1) - ox);
            const uint32_t ly0 = uint32_t(std::max(y0, oy) - oy), ly1 = uint32_t(std::min(y1, oy + kBin - 1) - oy);
            const size_t k = size_t(by) * size_t(bins_x_) + size_t(bx);
            entries_[bin_start_[k] + cursor[k]++] = BinnedSphere::make(p, lx0, lx1, ly0, ly1, type);
          }
      });
    }
  });
}

}  // namespace spume

#include "render/volume/bin_trace.h"

#include <algorithm>
#include <cmath>

#include <emmintrin.h>

namespace spume {
namespace {
constexpr int kTile = ScreenBins::kTile;
}  // namespace

// The bin's spheres in near-to-far order (buckets about a radius deep; particle order within), so
// each ray's chords arrive almost sorted by entry and sort_intervals is about one pass. The order
// only affects speed: chords are sorted by value before they are summed.
void order_bin(const BinnedSphere* b, const BinnedSphere* e, const Camera& cam, BinScratch& s) {
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
  // Then into the lists of the 2x2 tiles each touches, in the same order, with the rectangles
  // clipped to the tile and made relative to it. (Rectangles lie inside the image, so a sphere
  // never reaches a tile past its edge.)
  for (auto& l : s.tiles) l.clear();
  for (const BinnedSphere& sp : s.bin_sorted) {
    const int x0 = sp.x0(), x1 = sp.x1(), y0 = sp.y0(), y1 = sp.y1();
    for (int ty = y0 / kTile; ty <= y1 / kTile; ++ty)
      for (int tx = x0 / kTile; tx <= x1 / kTile; ++tx) {
        const int ox = tx * kTile, oy = ty * kTile;
        const uint32_t lx0 = uint32_t(std::max(x0, ox) - ox), lx1 = uint32_t(std::min(x1, ox + kTile - 1) - ox);
        const uint32_t ly0 = uint32_t(std::max(y0, oy) - oy), ly1 = uint32_t(std::min(y1, oy + kTile - 1) - oy);
        s.tiles[size_t(ty * 2 + tx)].push_back(BinnedSphere::make(sp.centre(), lx0, lx1, ly0, ly1, sp.type()));
      }
  }
}

namespace {

// Per ray of the tile, room for one chord per candidate sphere: the rectangles summed by a 2D
// difference array, so the chord loop below stores without a size check and without a branch.
void reserve_chords(size_t w, size_t h, size_t spp, const std::vector<BinnedSphere>& spheres, BinScratch& s) {
  std::array<uint32_t, (kTile + 1) * (kTile + 1)> diff{};
  for (const BinnedSphere& sp : spheres) {
    const size_t x0 = size_t(sp.x0()), x1 = size_t(sp.x1()) + 1, y0 = size_t(sp.y0()), y1 = size_t(sp.y1()) + 1;
    ++diff[y0 * (kTile + 1) + x0], ++diff[y1 * (kTile + 1) + x1];
    --diff[y0 * (kTile + 1) + x1], --diff[y1 * (kTile + 1) + x0];
  }
  s.ray_start.resize(w * h * spp + 1);
  s.ray_end.resize(w * h * spp);
  s.wanted.resize(w * h * spp);
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
        s.wanted[ri] = column[x] > 0;
        total += column[x];
      }
    }
  }
  s.ray_start[w * h * spp] = total;
  if (s.chords.size() < total) s.chords.resize(total);
}

// The tile's rays as arrays of doubles (direction x, y, z, t_in, t_out), for the chord loop.
void ray_columns(const TileRays& t, BinScratch& s) {
  const size_t n = t.rays.size();
  s.ray_soa.resize(5 * n);
  double* c = s.ray_soa.data();
  for (size_t i = 0; i < n; ++i) {
    const TileRay& r = t.rays[i];
    c[i] = r.direction.x(), c[n + i] = r.direction.y(), c[2 * n + i] = r.direction.z();
    c[3 * n + i] = r.t_in, c[4 * n + i] = r.t_out;
  }
}

// Every candidate chord of the tile's spheres into its ray's room (reserve_chords):
// ray_sphere_chord and the clip to [t_in, t_out] for two rays at once (SSE2, part of x86-64),
// without a branch: a miss (or a ray that misses the bounds, t_in > t_out) leaves t1 <= t0, and
// the slot is reused by the ray's next chord. The same double operations in the same order as the
// scalar code (Eigen's dot is (x + y) + z; std::max(a, b) is _mm_max_pd(b, a)), so the same bits.
// The square root was the loop's bottleneck; two lanes halve its count.
void tile_chords(const TileRays& t, const std::vector<BinnedSphere>& spheres, const Vec3d& o, const std::array<double, kDiffuseTypeCount>& r2s,
                 BinScratch& s) {
  const size_t n = t.rays.size(), spp = size_t(t.spp), w = size_t(t.w);
  ray_columns(t, s);
  const double *dx = s.ray_soa.data(), *dy = dx + n, *dz = dx + 2 * n, *tin = dx + 3 * n, *tout = dx + 4 * n;
  Interval* chords = s.chords.data();
  uint32_t* end = s.ray_end.data();
  const __m128d zero = _mm_setzero_pd();
  for (const BinnedSphere& sp : spheres) {
    const Vec3d oc = sp.centre().cast<double>() - o;
    const double oc2 = oc.squaredNorm(), r2 = r2s[sp.type()];
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

}  // namespace

const std::vector<uint8_t>& count_tile_candidates(int ox, int oy, int w, int h, int spp, BinScratch& s) {
  reserve_chords(size_t(w), size_t(h), size_t(spp), s.tiles[size_t((oy / kTile) * 2 + ox / kTile)], s);
  return s.wanted;
}

size_t trace_bin_tile(const TileRays& t, int ox, int oy, const Vec3d& origin, const std::array<double, kDiffuseTypeCount>& r2,
                      const VolumeShading& shading, BinScratch& s, std::vector<RaySample>& out,
                      std::vector<RayTypes>* types) {
  const std::vector<BinnedSphere>& spheres = s.tiles[size_t((oy / kTile) * 2 + ox / kTile)];
  tile_chords(t, spheres, origin, r2, s);
  size_t found = 0;
  for (size_t i = 0; i < t.rays.size(); ++i) {
    Interval* l = s.chords.data() + s.ray_start[i];
    const size_t n = s.ray_end[i] - s.ray_start[i];
    found += n;
    sort_intervals(l, n);
    out[i] = absorb_intervals(l, n, shading, water_of(t, t.rays[i]), types ? &(*types)[i] : nullptr);
  }
  return found;
}

}  // namespace spume

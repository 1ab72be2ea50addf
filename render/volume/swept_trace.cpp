#include "render/volume/swept_trace.h"

#include <algorithm>
#include <cmath>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume {
namespace {

struct PathBound {
  Vec3f centre;
  float radius;  // 0: not drawn
};

// The sphere around a particle's swept sphere: the midpoint of its path's ends, half the distance
// between them, the path's sag (spray) and the drawn radius.
PathBound path_bound(const Vec3f& c, const Vec3f& v, DiffuseType type, float radius, const DiffuseMotion& m) {
  if (!(radius > 0.0f)) return {c, 0.0f};
  const Vec3d cd = c.cast<double>(), vd = v.cast<double>();
  const bool falls = type == DiffuseType::Spray;
  auto at = [&](double t) -> Vec3d { return cd + t * vd + (falls ? 0.5 * t * t : 0.0) * m.gravity; };
  const Vec3d a = at(m.open), b = at(m.close);
  const double span = m.close - m.open, sag = falls ? m.gravity.norm() * span * span / 8.0 : 0.0;
  return {Vec3f((0.5 * (a + b)).cast<float>()), float(radius + 0.5 * (b - a).norm() + sag) * (1.0f + 1e-5f)};
}

// A tighter rectangle than the bounding sphere's: the path's pieces are straight, and a straight piece's
// swept sphere lies in the hull of its end spheres, whose projection lies in the box around theirs
// (both in front of the camera). False, leaving the rectangle as it was, when an end is not seen
// (behind the camera or off the image: the path may still cross the view between its ends).
bool tighten(const SphereProjector& projector, const Vec3f& c, const Vec3f& v, DiffuseType type, float radius,
             const DiffuseMotion& m, int& x0, int& y0, int& x1, int& y1) {
  std::array<PathPiece, kSprayPieces> pieces;
  const int n = path_pieces(c.cast<double>(), v.cast<double>(), type, m.open, m.close, m.gravity, pieces);
  int bx0 = INT32_MAX, by0 = INT32_MAX, bx1 = -1, by1 = -1;
  for (int k = 0; k <= n; ++k) {
    const Vec3d end = k < n ? pieces[size_t(k)].a : pieces[size_t(n - 1)].a + pieces[size_t(n - 1)].b;
    int ex0, ey0, ex1, ey1;
    if (!projector.pixel_rect(end.cast<float>(), radius * (1.0f + 1e-5f), ex0, ey0, ex1, ey1)) return false;
    bx0 = std::min(bx0, ex0), by0 = std::min(by0, ey0), bx1 = std::max(bx1, ex1), by1 = std::max(by1, ey1);
  }
  x0 = std::max(x0, bx0), y0 = std::max(y0, by0), x1 = std::min(x1, bx1), y1 = std::min(y1, by1);
  return true;
}

}  // namespace

SweptBins::SweptBins(DiffuseView frame, const DiffuseMotion& motion, const std::array<float, kDiffuseTypeCount>& radius,
                     const SphereProjector& projector, int width, int height) {
  const size_t n = frame.size();
  if (motion.velocities.size() != n)
    fail("motion blur: frame ", frame.index, " has ", n, " particles but ", motion.velocities.size(), " velocities");
  tiles_x_ = (width + kTile - 1) / kTile, tiles_y_ = (height + kTile - 1) / kTile;
  // Rectangles in parallel, in fixed batches; lists filled in particle order.
  std::vector<std::array<uint16_t, 4>> rect(n);
  std::vector<uint8_t> seen(n, 0);
  constexpr size_t kBatch = SphereProjector::kBatch;
  const size_t batches = (n + kBatch - 1) / kBatch;
  std::vector<Aabb> batch_bounds(batches);
  parallel_for(batches, 64, [&](size_t b0, size_t b1) {
    Vec3f centres[kBatch];
    float radii[kBatch];
    SphereProjector::Rects r;
    for (size_t b = b0; b < b1; ++b) {
      const size_t first = b * kBatch, count = std::min(kBatch, n - first);
      for (size_t k = 0; k < count; ++k) {
        const size_t i = first + k;
        const DiffuseType type = frame.types[i];
        const float rad = size_t(type) < size_t(kDiffuseTypeCount) ? radius[size_t(type)] : 0.0f;
        const PathBound pb = path_bound(frame.positions[i], motion.velocities[i], type, rad, motion);
        centres[k] = pb.centre, radii[k] = pb.radius;
        if (pb.radius > 0.0f) {
          if (!finite(pb.centre) || !std::isfinite(pb.radius))
            fail("motion blur: frame ", frame.index, ", particle ", i, ": its path over the shutter is not finite "
                 "(velocity ", motion.velocities[i].transpose(), " m/s)");
          batch_bounds[b].extend(pb.centre - Vec3f::Constant(pb.radius));
          batch_bounds[b].extend(pb.centre + Vec3f::Constant(pb.radius));
        }
      }
      projector.pixel_rects(centres, radii, count, r);
      for (size_t k = 0; k < count; ++k) {
        int x0 = r.x0[k], y0 = r.y0[k], x1 = r.x1[k], y1 = r.y1[k];
        if (x0 > x1) continue;
        const size_t i = first + k;
        if (x1 - x0 > 4 || y1 - y0 > 4)  // a streak: the sphere around it holds much it never covers
          tighten(projector, frame.positions[i], motion.velocities[i], frame.types[i], radius[size_t(frame.types[i])],
                  motion, x0, y0, x1, y1);
        seen[i] = 1;
        rect[i] = {uint16_t(x0), uint16_t(y0), uint16_t(x1), uint16_t(y1)};
      }
    }
  });
  for (const Aabb& b : batch_bounds) bounds_.extend(b);
  start_.assign(size_t(tiles_x_) * size_t(tiles_y_) + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    if (!seen[i]) continue;
    ++particles_;
    const auto& r = rect[i];
    for (int ty = r[1] / kTile; ty <= r[3] / kTile; ++ty)
      for (int tx = r[0] / kTile; tx <= r[2] / kTile; ++tx) ++start_[size_t(ty) * size_t(tiles_x_) + size_t(tx) + 1];
  }
  for (size_t t = 1; t < start_.size(); ++t) start_[t] += start_[t - 1];
  entries_.resize(start_.back());
  std::vector<size_t> fill(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < n; ++i) {
    if (!seen[i]) continue;
    const auto& r = rect[i];
    for (int ty = r[1] / kTile; ty <= r[3] / kTile; ++ty)
      for (int tx = r[0] / kTile; tx <= r[2] / kTile; ++tx)
        entries_[fill[size_t(ty) * size_t(tiles_x_) + size_t(tx)]++] = {uint32_t(i), r[0], r[1], r[2], r[3]};
  }
}

const std::vector<uint8_t>& swept_candidates(const SweptBins& bins, int x0, int y0, int w, int h, int spp,
                                             SweptTraceScratch& s) {
  s.wanted.assign(size_t(w) * size_t(h) * size_t(spp), 0);
  const size_t tile = size_t(y0 / SweptBins::kTile) * size_t(bins.tiles_x()) + size_t(x0 / SweptBins::kTile);
  for (const SweptBins::Entry& e : bins.tile(tile)) {
    const int ex0 = std::max(int(e.x0), x0) - x0, ex1 = std::min(int(e.x1), x0 + w - 1) - x0;
    const int ey0 = std::max(int(e.y0), y0) - y0, ey1 = std::min(int(e.y1), y0 + h - 1) - y0;
    for (int y = ey0; y <= ey1; ++y)
      std::fill_n(s.wanted.begin() + ptrdiff_t((size_t(y) * size_t(w) + size_t(ex0)) * size_t(spp)),
                  size_t(ex1 - ex0 + 1) * size_t(spp), uint8_t(1));
  }
  return s.wanted;
}

size_t trace_swept_tile(const TileRays& t, const SweptBins& bins, DiffuseView frame, const DiffuseMotion& motion,
                        const Vec3d& origin, const std::array<double, kDiffuseTypeCount>& r2, const VolumeShading& shading,
                        SweptTraceScratch& s, std::vector<RaySample>& out, std::vector<RayTypes>* types) {
  const size_t rays = t.rays.size(), spp = size_t(t.spp), w = size_t(t.w);
  if (s.chords.size() < rays) s.chords.resize(rays);
  for (size_t i = 0; i < rays; ++i) s.chords[i].clear();
  const size_t tile = size_t(t.y0 / SweptBins::kTile) * size_t(bins.tiles_x()) + size_t(t.x0 / SweptBins::kTile);
  std::array<PathPiece, kSprayPieces> pieces;
  std::array<EyePiece, kSprayPieces> seen;
  for (const SweptBins::Entry& e : bins.tile(tile)) {
    const DiffuseType type = frame.types[e.particle];
    const int n = path_pieces(frame.positions[e.particle].cast<double>(), motion.velocities[e.particle].cast<double>(), type,
                              motion.open, motion.close, motion.gravity, pieces);
    for (int k = 0; k < n; ++k) seen[size_t(k)] = eye_piece(pieces[size_t(k)], r2[size_t(type)], origin);
    const int ex0 = std::max(int(e.x0), t.x0) - t.x0, ex1 = std::min(int(e.x1), t.x0 + t.w - 1) - t.x0;
    const int ey0 = std::max(int(e.y0), t.y0) - t.y0, ey1 = std::min(int(e.y1), t.y0 + t.h - 1) - t.y0;
    for (int y = ey0; y <= ey1; ++y)
      for (size_t ri = (size_t(y) * w + size_t(ex0)) * spp, end = (size_t(y) * w + size_t(ex1) + 1) * spp; ri < end; ++ri) {
        const TileRay& ray = t.rays[ri];
        if (ray.misses()) continue;
        for (int k = 0; k < n; ++k) {
          SweptChord c;
          if (!swept_chord(seen[size_t(k)], ray.direction, c)) continue;
          c.type = uint32_t(type), c.particle = e.particle;
          s.chords[ri].push_back(c);
        }
      }
  }
  size_t found = 0;
  for (size_t i = 0; i < rays; ++i) {
    if (s.chords[i].empty()) continue;
    found += s.chords[i].size();
    out[i] = absorb_swept(s.chords[i], t.rays[i].t_in, t.rays[i].t_out, shading, water_of(t, t.rays[i]), s.absorb,
                          types ? &(*types)[i] : nullptr);
  }
  return found;
}

}  // namespace spume

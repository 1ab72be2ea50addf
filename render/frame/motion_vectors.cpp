#include "render/frame/motion_vectors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "render/surface/sparse_bins.h"
#include "render/volume/swept_trace.h"
#include "sim/core/parallel.h"

namespace spume {
namespace {

using Vec2d = Eigen::Vector2d;

// A camera's pinhole, worked out once: pixel coordinates (x right, y down, as the image's rows) of
// world points, and the unnormalised ray through a pixel (forward component 1).
struct Pinhole {
  explicit Pinhole(const Camera& cam) : origin(cam.position.cast<double>()), width(cam.width), height(cam.height) {
    Vec3f r, u, b;
    cam.basis(r, u, b);
    right = r.cast<double>(), up = u.cast<double>(), forward = -b.cast<double>();
    tan_y = std::tan(0.5 * double(cam.fov_y_degrees) * std::numbers::pi / 180.0);
    tan_x = tan_y * double(cam.width) / double(cam.height);
  }
  // False behind the camera.
  bool project(const Vec3d& p, Vec2d& out) const {
    const Vec3d v = p - origin;
    const double z = v.dot(forward);
    if (!(z > 1e-9)) return false;
    out = Vec2d((v.dot(right) / z / tan_x + 1.0) * 0.5 * width, (1.0 - v.dot(up) / z / tan_y) * 0.5 * height);
    return true;
  }
  Vec3d ray(int x, int y) const {
    const double sx = (2.0 * (x + 0.5) / width - 1.0) * tan_x, sy = (1.0 - 2.0 * (y + 0.5) / height) * tan_y;
    return sx * right + sy * up + forward;
  }
  Vec3d origin, right, up, forward;
  double tan_x, tan_y;
  int width, height;
};

struct Pinholes {
  explicit Pinholes(const MotionScene& m) : previous(m.previous), now(m.now), next(m.next), dt(m.frame_seconds) {}
  Pinhole previous, now, next;
  double dt;

  // {forward u, forward v, backward u, backward v} of a point at p moving at u (m/s); v is up.
  Rgba motion(const Vec3d& p, const Vec3d& u) const {
    Vec2d a, b, c;
    if (!now.project(p, a) || !next.project(p + dt * u, b) || !previous.project(p - dt * u, c)) return {0, 0, 0, 0};
    return {float(b.x() - a.x()), float(a.y() - b.y()), float(c.x() - a.x()), float(a.y() - c.y())};
  }
};

// The fluid's velocity near a point: particles binned (the surface reconstruction's index) in cells of
// the support h, so the particles within h of a point lie in its cell's 27.
class FluidVelocity {
 public:
  FluidVelocity(std::span<const Vec3f> x, std::span<const Vec3f> v, float h) : v_(v), h_(h) {
    if (v.empty() || x.size() != v.size() || !(h > 0.0f)) return;
    Aabb box;
    for (const Vec3f& p : x) box.extend(p);
    bins_.build(x, box.min, h);
    on_ = true;
  }

  Vec3f at(const Vec3f& p) const {
    if (!on_) return Vec3f::Zero();
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = int(std::floor((p[a] - bins_.origin()[a]) / h_));
    const float h2 = h_ * h_;
    double wsum = 0.0;
    Vec3d vsum = Vec3d::Zero();
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int i = c[0] + dx, j = c[1] + dy, k = c[2] + dz;
          if (std::min({i, j, k}) < 0 || std::max({i, j, k}) > SparseBins::kMaxCoord) continue;
          const int64_t cell = bins_.find(i, j, k);
          if (cell == SparseBins::kMissing) continue;
          const std::span<const Vec3f> points = bins_.points(size_t(cell));
          const std::span<const uint32_t> index = bins_.indices(size_t(cell));
          for (size_t e = 0; e < points.size(); ++e) {
            const float d2 = (points[e] - p).squaredNorm();
            if (d2 >= h2) continue;
            const double q = 1.0 - double(d2 / h2), w = q * q * q;
            wsum += w, vsum += w * v_[index[e]].cast<double>();
          }
        }
    return wsum > 0.0 ? Vec3f((vsum / wsum).cast<float>()) : Vec3f::Zero();
  }

 private:
  std::span<const Vec3f> v_;
  float h_;
  SparseBins bins_;
  bool on_ = false;
};

// Distance from p to a solid's surface (a tank's: its walls and floor).
float surface_distance(const Solid& s, const Vec3f& p) {
  if (s.kind == Solid::Kind::Sphere) return std::abs((p - s.center).norm() - s.radius);
  const Vec3f c = s.centre(), half = 0.5f * (s.max - s.min);
  const Vec3f q = (s.orientation.conjugate() * (p - c)).cwiseAbs();
  if (s.kind == Solid::Kind::Box) {
    const Vec3f out = (q - half).cwiseMax(0.0f);
    return out.squaredNorm() > 0.0f ? out.norm() : (half - q).minCoeff();
  }
  float d = std::numeric_limits<float>::infinity();  // tank: the nearest wall's plane
  for (int a = 0; a < 3; ++a) {
    const float lo = p[a] - s.min[a], hi = s.max[a] - p[a];
    d = std::min(d, std::abs(lo));
    if (!(s.open_top && a == s.up_axis)) d = std::min(d, std::abs(hi));
  }
  return d;
}

Vec3f solid_velocity(const SolidSet* solids, const Vec3f& p, float reach) {
  if (!solids) return Vec3f::Zero();
  const Solid* nearest = nullptr;
  float best = reach;
  for (const Solid& s : solids->solids()) {
    const float d = surface_distance(s, p);
    if (d <= best) best = d, nearest = &s;
  }
  return nearest ? nearest->velocity_at(p) : Vec3f::Zero();
}

}  // namespace

std::vector<Rgba> motion_vectors(const MotionScene& m, const SurfaceImage& surface, const VolumeImage* volume) {
  const Camera& cam = m.now;
  const int w = cam.width, h = cam.height;
  std::vector<Rgba> out(size_t(w) * size_t(h), Rgba{0, 0, 0, 0});
  const FluidVelocity fluid(m.fluid_positions, m.fluid_velocities, m.fluid_support);
  const Pinholes pin(m);
  parallel_for(size_t(h), 8, [&](size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t p = y * size_t(w) + size_t(x);
        const Vec3d dir = pin.now.ray(x, int(y));  // forward component 1: planar depth scales it
        const float depth = surface.depth[p];
        if (!std::isfinite(depth)) {  // sky: a point far away, moved by the camera only
          out[p] = pin.motion(pin.now.origin + 1e6 * dir, Vec3d::Zero());
          continue;
        }
        const Vec3d point = pin.now.origin + double(depth) * dir;
        const bool water = depth < surface.opaque_depth[p];
        const Vec3f at = point.cast<float>();
        const Vec3f u = water ? fluid.at(at) : solid_velocity(m.solids, at, 1e-3f * depth + 1e-4f);
        out[p] = pin.motion(point, u.cast<double>());
      }
  });
  if (!volume || !m.diffuse || m.diffuse_velocities.size() != m.diffuse->size()) return out;

  // The diffuse material: each particle's screen motion, weighted by its chord along the pixel's
  // central ray in front of the nearest opaque surface. Tiles in parallel, particles in order.
  const DiffuseView frame(*m.diffuse);
  const SweptBins bins(frame, DiffuseMotion{m.diffuse_velocities, 0.0, 0.0, Vec3d::Zero()}, m.radius,
                       SphereProjector(cam, 0.5, 0.5), w, h);
  const int tiles_x = bins.tiles_x(), tiles_y = (h + SweptBins::kTile - 1) / SweptBins::kTile;
  parallel_for(size_t(tiles_x) * size_t(tiles_y), 1, [&](size_t t0, size_t t1) {
    std::vector<double> weight;
    std::vector<std::array<double, 4>> sum;
    for (size_t t = t0; t < t1; ++t) {
      const int ox = int(t % size_t(tiles_x)) * SweptBins::kTile, oy = int(t / size_t(tiles_x)) * SweptBins::kTile;
      const int tw = std::min(SweptBins::kTile, w - ox), th = std::min(SweptBins::kTile, h - oy);
      weight.assign(size_t(tw) * size_t(th), 0.0);
      sum.assign(weight.size(), {0, 0, 0, 0});
      for (const SweptBins::Entry& e : bins.tile(t)) {
        const Vec3d c = frame.positions[e.particle].cast<double>();
        const Rgba mv = pin.motion(c, m.diffuse_velocities[e.particle].cast<double>());
        const double r = m.radius[size_t(frame.types[e.particle])], r2 = r * r;
        const Vec3d oc = c - pin.now.origin;
        for (int y = std::max(int(e.y0), oy); y <= std::min(int(e.y1), oy + th - 1); ++y)
          for (int x = std::max(int(e.x0), ox); x <= std::min(int(e.x1), ox + tw - 1); ++x) {
            const size_t p = size_t(y) * size_t(w) + size_t(x);
            const Vec3d ray = pin.now.ray(x, y);
            const double norm = ray.norm();  // the ray's forward component is 1: planar depth x norm = distance
            const Vec3d d = ray / norm;
            const double tc = oc.dot(d), b2 = oc.squaredNorm() - tc * tc;
            if (b2 >= r2) continue;
            const double stop = double(surface.opaque_depth[p]) * norm;  // the opaque surface along this ray
            const double half = std::sqrt(r2 - b2), len = std::min(tc + half, stop) - std::max(tc - half, 0.0);
            if (!(len > 0.0)) continue;
            const size_t l = size_t(y - oy) * size_t(tw) + size_t(x - ox);
            weight[l] += len;
            for (int k = 0; k < 4; ++k) sum[l][size_t(k)] += len * mv[size_t(k)];
          }
      }
      for (int ly = 0; ly < th; ++ly)
        for (int lx = 0; lx < tw; ++lx) {
          const size_t l = size_t(ly) * size_t(tw) + size_t(lx), p = size_t(oy + ly) * size_t(w) + size_t(ox + lx);
          if (!(weight[l] > 0.0)) continue;
          const float opacity = 1.0f - volume->transmittance[p];
          for (int k = 0; k < 4; ++k)
            out[p][size_t(k)] = float(opacity * (sum[l][size_t(k)] / weight[l]) + (1.0f - opacity) * out[p][size_t(k)]);
        }
    }
  });
  return out;
}

}  // namespace spume

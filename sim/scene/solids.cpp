#include "solids.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "diffuse/kernels.h"

namespace spume {
namespace {

// Signed distance to a box's surface, positive outside, with the outward normal of the nearest face.
float box_distance(const Vec3f& p, const Vec3f& lo, const Vec3f& hi, Vec3f& normal) {
  const Vec3f centre = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
  const Vec3f q = (p - centre).cwiseAbs() - half;
  const Vec3f outside = q.cwiseMax(0.0f);
  if (outside.squaredNorm() > 0.0f) {
    const Vec3f nearest = p.cwiseMax(lo).cwiseMin(hi);
    normal = (p - nearest).normalized();
    return outside.norm();
  }
  int axis = 0;
  q.maxCoeff(&axis);  // the face we are closest to from inside
  normal = Vec3f::Zero();
  normal[axis] = p[axis] >= centre[axis] ? 1.0f : -1.0f;
  return q[axis];
}

}  // namespace

float SolidSet::solid_volume_within(const Vec3f& p, float h) const {
  float volume = 0.0f;
  for (const Solid& s : solids_) {
    switch (s.kind) {
      case Solid::Kind::Tank:
        for (int a = 0; a < 3; ++a) {
          if (a != s.up_axis && p[s.up_axis] > s.max[s.up_axis]) continue;  // above the side walls
          volume += sphere_cap_volume(p[a] - s.min[a], h);
          if (!(s.open_top && a == s.up_axis)) volume += sphere_cap_volume(s.max[a] - p[a], h);
        }
        break;
      case Solid::Kind::Box: {
        Vec3f n;
        volume += sphere_cap_volume(box_distance(p, s.min, s.max, n), h);
        break;
      }
      case Solid::Kind::Sphere:
        volume += sphere_cap_volume((p - s.center).norm() - s.radius, h);
        break;
    }
  }
  return std::min(volume, 4.0f / 3.0f * std::numbers::pi_v<float> * h * h * h);
}

bool SolidSet::push_out(Vec3f& p, Vec3f& v, float skin) const {
  bool moved = false;
  auto push = [&](const Vec3f& normal, float depth) {  // depth > 0: how far p is inside along -normal
    p += (depth + skin) * normal;
    const float vn = v.dot(normal);
    if (vn < 0.0f) v -= vn * normal;
    moved = true;
  };
  for (const Solid& s : solids_) {
    switch (s.kind) {
      case Solid::Kind::Tank:
        for (int a = 0; a < 3; ++a) {
          if (a != s.up_axis && p[s.up_axis] > s.max[s.up_axis]) continue;  // passing over a side wall
          Vec3f n = Vec3f::Zero();
          if (p[a] < s.min[a]) {
            n[a] = 1.0f;
            push(n, s.min[a] - p[a]);
          }
          if (!(s.open_top && a == s.up_axis) && p[a] > s.max[a]) {
            n[a] = -1.0f;
            push(n, p[a] - s.max[a]);
          }
        }
        break;
      case Solid::Kind::Box: {
        Vec3f n;
        const float d = box_distance(p, s.min, s.max, n);
        if (d < 0.0f) push(n, -d);
        break;
      }
      case Solid::Kind::Sphere: {
        const Vec3f r = p - s.center;
        const float len = r.norm();
        if (len < s.radius) push(len > 0.0f ? Vec3f(r / len) : Vec3f::UnitY(), s.radius - len);
        break;
      }
    }
  }
  return moved;
}

}  // namespace spume

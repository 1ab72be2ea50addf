#include "render/surface/mesh_primitives.h"

#include <cmath>
#include <numbers>

#include "sim/core/error.h"

namespace spume {

TriangleMesh make_quad_mesh(const Vec3f& corner, const Vec3f& u, const Vec3f& v) {
  TriangleMesh m;
  const Vec3f n = u.cross(v).normalized();
  m.vertices = {corner, corner + u, corner + u + v, corner + v};
  m.normals.assign(4, n);
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TriangleMesh make_box_mesh(const Vec3f& min, const Vec3f& max) {
  TriangleMesh m;
  const Vec3f size = max - min;
  for (int axis = 0; axis < 3; ++axis) {
    // u x v = +axis, so the face on the max side faces outward as given and the min side is flipped.
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const Vec3f u = Vec3f::Unit(a1) * size[a1], v = Vec3f::Unit(a2) * size[a2];
    Vec3f hi = min;
    hi[axis] = max[axis];
    m.append(make_quad_mesh(hi, u, v));
    m.append(make_quad_mesh(min, v, u));
  }
  return m;
}

TriangleMesh make_sphere_mesh(const Vec3f& center, float radius, int rings, int segments) {
  if (rings < 2 || segments < 3) fail("sphere mesh: needs rings >= 2 and segments >= 3, got ", rings, ", ", segments);
  TriangleMesh m;
  const float pi = std::numbers::pi_v<float>;
  for (int i = 0; i <= rings; ++i) {
    const float theta = pi * float(i) / float(rings);  // from +y down
    for (int j = 0; j <= segments; ++j) {
      const float phi = 2.0f * pi * float(j) / float(segments);
      const Vec3f n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      m.vertices.push_back(center + radius * n);
      m.normals.push_back(n);
    }
  }
  const uint32_t row = uint32_t(segments + 1);
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = uint32_t(i) * row + uint32_t(j), b = a + row;
      // Poles would give zero-area triangles: skip them.
      if (i > 0) m.indices.insert(m.indices.end(), {a, b, a + 1});
      if (i + 1 < rings) m.indices.insert(m.indices.end(), {a + 1, b, b + 1});
    }
  return m;
}

}  // namespace spume

#pragma once
// Simple closed meshes for scene solids and tests, wound counter-clockwise seen from outside, with
// outward normals.
#include "sim/core/vec.h"
#include "render/surface/triangle_mesh.h"

namespace spume {

// Axis-aligned box with flat faces (4 vertices per face, so normals are sharp), m.
TriangleMesh make_box_mesh(const Vec3f& min, const Vec3f& max);

// Latitude-longitude sphere: `rings` latitude bands (>= 2) and `segments` longitudes (>= 3).
TriangleMesh make_sphere_mesh(const Vec3f& center, float radius, int rings = 32, int segments = 64);

// One-sided rectangle corner, corner + u, corner + u + v, corner + v; facing u x v.
TriangleMesh make_quad_mesh(const Vec3f& corner, const Vec3f& u, const Vec3f& v);

}  // namespace spume

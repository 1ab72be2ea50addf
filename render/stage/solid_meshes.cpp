#include "solid_meshes.h"

#include "surface/mesh_primitives.h"

namespace spume {
namespace {

// The walls of a tank whose inside faces the eye, each a quad facing into the tank.
TriangleMesh cutaway_tank(const Solid& tank, const Vec3f& eye) {
  TriangleMesh mesh;
  const Vec3f lo = tank.min, hi = tank.max;
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    Vec3f u = Vec3f::Zero(), v = Vec3f::Zero();
    u[a] = hi[a] - lo[a];
    v[b] = hi[b] - lo[b];
    for (int side = 0; side < 2; ++side) {
      if (axis == tank.up_axis && side == 1 && tank.open_top) continue;
      const float plane = side == 0 ? lo[axis] : hi[axis];
      // The inside of the wall at lo faces +axis: the eye sees it when eye[axis] > plane.
      const bool seen_from_inside = side == 0 ? eye[axis] > plane : eye[axis] < plane;
      if (!seen_from_inside) continue;
      Vec3f corner = lo;
      corner[axis] = plane;
      // u x v points along +axis; the low wall faces +axis, the high wall -axis (swap u, v).
      mesh.append(side == 0 ? make_quad_mesh(corner, u, v) : make_quad_mesh(corner, v, u));
    }
  }
  return mesh;
}

// A rotated box's min/max are its extent in its own frame about its centre.
void rotate_about(TriangleMesh& mesh, const Quatf& orientation, const Vec3f& centre) {
  const Eigen::Matrix3f rotation = orientation.toRotationMatrix();
  for (Vec3f& v : mesh.vertices) v = centre + rotation * (v - centre);
  for (Vec3f& n : mesh.normals) n = rotation * n;
}

}  // namespace

std::vector<SolidMesh> solid_meshes(const SolidSet& solids, const Vec3f& eye) {
  std::vector<SolidMesh> meshes;
  for (const Solid& s : solids.solids()) {
    SolidMesh m;
    switch (s.kind) {
      case Solid::Kind::Tank:
        m.mesh = cutaway_tank(s, eye);
        m.albedo = Vec3f(0.62f, 0.64f, 0.66f);
        break;
      case Solid::Kind::Box:
        m.mesh = make_box_mesh(s.min, s.max);
        if (s.rotated()) rotate_about(m.mesh, s.orientation, s.centre());
        m.albedo = Vec3f(0.72f, 0.45f, 0.25f);
        break;
      case Solid::Kind::Sphere:
        m.mesh = make_sphere_mesh(s.center, s.radius);
        m.albedo = Vec3f(0.5f, 0.5f, 0.5f);
        break;
    }
    if (!m.mesh.empty()) meshes.push_back(std::move(m));
  }
  return meshes;
}

}  // namespace spume

#include "render/stage/solid_meshes.h"

#include "render/surface/mesh_primitives.h"

namespace spume {
namespace {

// The walls of a tank whose inside faces the eye, each a quad facing into the tank, and what casts
// their shadow: each wall whose outside faces the sun (only those shade the inside) as a closed slab,
// its inner face the wall and its outer face moved out by the shadow pass (the normals of
// SolidMesh::shadow_caster); the other walls as they are. Corners are taken from min/max as they are,
// so walls that meet share their edge bit for bit.
struct CutawayTank {
  TriangleMesh walls, shadow_caster;
};

CutawayTank cutaway_tank(const Solid& tank, const Vec3f& eye, const Vec3f& sun) {
  // Corner k of the box: bit `axis` of k picks max along that axis.
  auto corner = [&](int k) {
    Vec3f c;
    for (int axis = 0; axis < 3; ++axis) c[axis] = (k >> axis & 1) ? tank.max[axis] : tank.min[axis];
    return c;
  };
  bool drawn[3][2] = {};
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      if (axis == tank.up_axis && side == 1 && tank.open_top) continue;
      // The inside of the wall at min faces +axis: the eye sees it when eye[axis] > plane.
      drawn[axis][side] = side == 0 ? eye[axis] > tank.min[axis] : eye[axis] < tank.max[axis];
    }
  // Thickened: the wall's outside (-axis at min, +axis at max) faces the sun. Thin walls stay thin, so
  // a floor under a sun from above never reaches below the ground it stands on.
  bool thick[3][2] = {};
  for (int axis = 0; axis < 3; ++axis)
    thick[axis][0] = drawn[axis][0] && sun[axis] < 0, thick[axis][1] = drawn[axis][1] && sun[axis] > 0;
  // A slab's outer corner moves out of every thickened wall the corner lies on, so where two meet their
  // slabs overlap past the edge and the outer faces meet.
  auto outward = [&](int k) {
    Vec3f p = Vec3f::Zero();
    for (int axis = 0; axis < 3; ++axis) {
      const int side = k >> axis & 1;
      if (thick[axis][side]) p[axis] = side ? 1.0f : -1.0f;
    }
    return p;
  };
  CutawayTank out;
  TriangleMesh& slabs = out.shadow_caster;
  auto add_quad = [](TriangleMesh& m, uint32_t q0, uint32_t q1, uint32_t q2, uint32_t q3) {
    m.indices.insert(m.indices.end(), {q0, q1, q2, q0, q2, q3});
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int a = 1 << (axis + 1) % 3, b = 1 << (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      if (!drawn[axis][side]) continue;
      const int base = side << axis;
      // Counter-clockwise seen from inside: the low wall faces +axis (corners 0, a, a+b, b), the high
      // wall -axis (the other way round).
      const int quad[4] = {base, base | (side ? b : a), base | a | b, base | (side ? a : b)};
      const Vec3f facing = Vec3f::Unit(axis) * (side ? -1.0f : 1.0f);
      const uint32_t w = uint32_t(out.walls.vertices.size());
      for (int k : quad) out.walls.vertices.push_back(corner(k)), out.walls.normals.push_back(facing);
      add_quad(out.walls, w, w + 1, w + 2, w + 3);
      // The wall as it is (corners 0-3 stay); a slab adds outer corners 4-7, which move out, and the
      // outer and four side faces.
      const uint32_t v = uint32_t(slabs.vertices.size());
      for (int k : quad) slabs.vertices.push_back(corner(k)), slabs.normals.push_back(Vec3f::Zero());
      add_quad(slabs, v, v + 1, v + 2, v + 3);
      if (!thick[axis][side]) continue;
      for (int k : quad) slabs.vertices.push_back(corner(k)), slabs.normals.push_back(outward(k));
      add_quad(slabs, v + 4, v + 5, v + 6, v + 7);
      for (uint32_t j = 0; j < 4; ++j) add_quad(slabs, v + j, v + (j + 1) % 4, v + 4 + (j + 1) % 4, v + 4 + j);
    }
  }
  return out;
}

// A rotated box's min/max are its extent in its own frame about its centre.
void rotate_about(TriangleMesh& mesh, const Quatf& orientation, const Vec3f& centre) {
  const Eigen::Matrix3f rotation = orientation.toRotationMatrix();
  for (Vec3f& v : mesh.vertices) v = centre + rotation * (v - centre);
  for (Vec3f& n : mesh.normals) n = rotation * n;
}

}  // namespace

std::vector<SolidMesh> solid_meshes(const SolidSet& solids, const Vec3f& eye, const Vec3f& sun_direction) {
  std::vector<SolidMesh> meshes;
  for (const Solid& s : solids.solids()) {
    SolidMesh m;
    switch (s.kind) {
      case Solid::Kind::Tank: {
        CutawayTank tank = cutaway_tank(s, eye, sun_direction);
        m.mesh = std::move(tank.walls);
        m.shadow_caster = std::move(tank.shadow_caster);
        m.albedo = Vec3f(0.62f, 0.64f, 0.66f);
        break;
      }
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

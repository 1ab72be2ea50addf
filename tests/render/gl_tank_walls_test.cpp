// A tank's walls where they meet, in the OSMesa pass: a wall in the shadow of the wall it meets stays
// in shadow right up to the edge (no bright line of light leaking along it), and the edge shows a
// wall on every pixel (no crack showing what lies behind).
#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>
#include <string>

#include "sim/core/error.h"
#include "render/gl/surface_pass.h"
#include "render/image/png_io.h"
#include "render/frame/frame_renderer.h"
#include "render/stage/solid_meshes.h"

namespace spume {
namespace {

float luminance(const Vec3f& c) { return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z(); }

// An open unit tank, the default sun (towards -x, up and +z), and a camera in front of the tank
// (outside its +z wall, which the cutaway leaves out) looking closely into the corner where the
// left wall (x = 0), the back wall (z = 0) and the floor (y = 0) meet.
//
// Worked by hand, with s = (-0.45, 0.62, 0.64) (normalised: |s| = 1.0):
//  - The left wall's inside faces +x, away from the sun (n.s = -0.45): only sky and ground light it.
//  - A back-wall point (d, y, 0) sends its ray to the sun through x = 0 after d / 0.45 m, having risen
//    0.62 d / 0.45 = 1.38 d and moved 0.64 d / 0.45 = 1.42 d along z: for d <= 0.1 and y <= 0.8 that
//    is inside the left wall (y < 0.94 < 1, z < 0.15 < 1), so the back wall there is in the left
//    wall's shadow: sky and ground light only, like the left wall (both vertical, so the same light).
//  - A floor point (d, 0, z) likewise meets x = 0 at height 1.38 d and z + 1.42 d: in the left wall's
//    shadow for d <= 0.1 and z <= 0.6.
// So every pixel that sees one of these three patches must show the shadowed colour
// albedo * irradiance(n, visibility 0) / pi, whatever the distance to the edges. A light leak along an
// edge shows the lit colour (the sun adds about 2.2 x 0.64 = 1.4 to the back wall's irradiance of
// about 0.9 from sky and ground: 2.6 times as bright) and a crack the ground behind the tank; the
// margin of a quarter of the lit-minus-shadowed difference passes only a shadow, and is far above the
// 16-bit float targets' rounding (1e-3 relative).
//
// Mirrored (x -> 1 - x, the sun towards +x), the right wall shades the back wall and the floor.
struct TankCorner {
  bool mirrored;
  SolidSet solids;
  Camera cam;
  Environment env;

  explicit TankCorner(bool mirror) : mirrored(mirror) {
    Solid tank;
    tank.kind = Solid::Kind::Tank;
    tank.min = Vec3f::Zero(), tank.max = Vec3f::Ones();
    solids = SolidSet({tank});
    cam.position = Vec3f(0.5f, 0.8f, 1.6f), cam.target = Vec3f(mirror ? 0.97f : 0.03f, 0.1f, 0.03f);
    cam.fov_y_degrees = 10;
    cam.width = cam.height = 240;  // about 1.3 mm a pixel at the corner
    env.ground_height = -0.01f;    // just under the floor, so the floor is the tank's
    if (mirror) env.sun_direction.x() = -env.sun_direction.x();
  }

  // Which shadowed patch the pixel's ray meets first, and its inside normal; none: Vec3f::Zero().
  Vec3f patch_normal(int x, int y) const {
    Ray r = cam.ray(x + 0.5f, y + 0.5f);
    if (mirrored) r.origin.x() = 1 - r.origin.x(), r.direction.x() = -r.direction.x();
    auto at = [&](int axis) { return r.origin + r.direction * (-r.origin[axis] / r.direction[axis]); };
    // The camera is on the inside of each of the three planes (x, y > 0 and the ray heads to z = 0
    // from z > 1 through the open front), so the first plane the ray crosses is the wall it sees.
    float best = INFINITY;
    Vec3f normal = Vec3f::Zero();
    for (int axis = 0; axis < 3; ++axis) {
      if (r.direction[axis] >= 0) continue;
      const Vec3f p = at(axis);
      const float t = (p - r.origin).norm();
      if (t >= best) continue;
      bool inside_patch = false;
      if (axis == 2) inside_patch = p.x() >= 0 && p.x() <= 0.1f && p.y() >= 0.05f && p.y() <= 0.8f;  // back
      if (axis == 0) inside_patch = p.z() >= 0 && p.z() <= 0.1f && p.y() >= 0.05f && p.y() <= 0.8f;  // left
      if (axis == 1) inside_patch = p.x() >= 0 && p.x() <= 0.1f && p.z() >= 0.05f && p.z() <= 0.6f;  // floor
      best = t;
      normal = inside_patch ? Vec3f(Vec3f::Unit(axis)) : Vec3f::Zero();
    }
    if (mirrored) normal.x() = -normal.x();
    return normal;
  }
};

TEST(GlTankWalls, WallsInShadowStayDarkUpToTheEdgeWhereTheyMeet) {
  SurfacePass pass(SurfacePassOptions{.supersample = 1, .gl = {}});
  for (bool mirrored : {false, true}) {
    SCOPED_TRACE(mirrored ? "the right wall shades (sun towards +x)" : "the left wall shades (sun towards -x)");
    const TankCorner c(mirrored);
    const std::vector<SolidMesh> meshes = solid_meshes(c.solids, c.cam.position, c.env.sun_direction);
    ASSERT_EQ(meshes.size(), 1u);
    SurfaceScene scene;
    scene.environment = c.env;
    scene.solids.push_back(scene_solid(meshes[0]));
    const SurfaceImage img = pass.render(scene, c.cam);
    const char* name = mirrored ? "gl_tank_corner_right.png" : "gl_tank_corner.png";
    write_png(std::filesystem::path(SPUME_OUT_DIR) / "tests" / name, to_srgb8(img.colour));

    const Vec3f albedo = meshes[0].albedo;
    const float pi = std::numbers::pi_v<float>;
    auto radiance = [&](const Vec3f& n, float sun) {
      return luminance(albedo.cwiseProduct(c.env.irradiance(n, sun)) / pi);
    };
    // What the sun adds to the walls in shadow here (the back wall and the floor), the smaller of the two.
    const float sun_adds = std::min(radiance(Vec3f::UnitZ(), 1) - radiance(Vec3f::UnitZ(), 0),
                                    radiance(Vec3f::UnitY(), 1) - radiance(Vec3f::UnitY(), 0));
    ASSERT_GT(sun_adds, 0.3f * radiance(Vec3f::UnitZ(), 0)) << "the sun must make a visible difference";
    int checked = 0, near_edge = 0, too_bright = 0, too_dark = 0;
    std::string worst;
    float worst_excess = 0;
    for (int y = 0; y < c.cam.height; ++y)
      for (int x = 0; x < c.cam.width; ++x) {
        const Vec3f n = c.patch_normal(x, y);
        if (n == Vec3f::Zero()) continue;
        const float shadowed = radiance(n, 0), seen = luminance(img.colour.at(x, y));
        if (seen > shadowed + 0.25f * sun_adds) ++too_bright;
        if (seen < 0.97f * shadowed) ++too_dark;
        if (seen - shadowed > worst_excess) {
          worst_excess = seen - shadowed;
          worst = str("(", x, ", ", y, ") on the ", n.x() != 0 ? "side wall" : n.y() > 0 ? "floor" : "back wall",
                      ": ", seen, " where the shadowed wall is ", shadowed, " and the sun adds ", sun_adds);
        }
        ++checked;
        // Pixels whose neighbour sees another patch or another wall: the edges themselves (the vertical
        // edge crosses most rows, the floor's two edges the lower part of the view).
        if (c.patch_normal(x + 1, y) != n || c.patch_normal(x, y + 1) != n) ++near_edge;
      }
    EXPECT_EQ(too_bright, 0) << "of " << checked << " pixels; brightest above the shadow: " << worst;
    EXPECT_EQ(too_dark, 0) << "of " << checked << " pixels";
    EXPECT_GT(checked, c.cam.width * c.cam.height / 4) << "the patches fill much of the view";
    EXPECT_GT(near_edge, c.cam.height) << "the edges cross the view";
  }
}

}  // namespace
}  // namespace spume

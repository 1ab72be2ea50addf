// The OSMesa surface pass: geometry and depth against analytic answers, the water material against
// the shading model evaluated on the CPU for a flat water body, and context handling.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "render/gl/surface_pass.h"
#include "render/image/png_io.h"
#include "render/surface/mesh_primitives.h"

namespace spume {
namespace {

// One pass (one context) for the whole test binary: contexts are created once per run.
SurfacePass& pass() {
  static SurfacePass p(SurfacePassOptions{.supersample = 1, .gl = {}});
  return p;
}

void save(const SurfaceImage& image, const char* name) {
  write_png(std::filesystem::path(SPUME_OUT_DIR) / "tests" / name, to_srgb8(image.colour));
}

float luminance(const Vec3f& c) { return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z(); }

// Relative colour difference, per channel against the larger value.
float rel_diff(const Vec3f& a, const Vec3f& b) {
  float worst = 0;
  for (int i = 0; i < 3; ++i)
    worst = std::max(worst, std::abs(a[i] - b[i]) / std::max({std::abs(a[i]), std::abs(b[i]), 1e-3f}));
  return worst;
}

Camera sphere_camera() {
  Camera c;
  c.position = Vec3f(0, 0, 3), c.target = Vec3f::Zero(), c.fov_y_degrees = 40;
  c.width = 161, c.height = 91;  // odd: the centre pixel's ray is the view axis
  return c;
}

TEST(GlSurfacePass, UnitSphereCoversTheCentreAtTheRightDepth) {
  const TriangleMesh sphere = make_sphere_mesh(Vec3f::Zero(), 1.0f, 64, 128);
  SurfaceScene scene;
  scene.solids.push_back({&sphere, Vec3f(0.7f, 0.2f, 0.2f), Vec3f::Zero()});
  scene.environment.ground = false;
  const Camera cam = sphere_camera();
  SurfacePassStats stats;
  const SurfaceImage img = pass().render(scene, cam, &stats);
  save(img, "gl_sphere.png");
  EXPECT_TRUE(stats.used_gl);
  const int cx = cam.width / 2, cy = cam.height / 2;
  const Vec3f centre = img.colour.at(cx, cy),
              sky_centre = scene.environment.sky(cam.ray(cx + 0.5f, cy + 0.5f).direction, true);
  EXPECT_GT(rel_diff(centre, sky_centre), 0.3f) << "the centre shows the sphere, not the sky";
  EXPECT_GT(centre.x(), 2 * centre.z()) << "red albedo";
  // Nearest point on the axis: distance 3 - 1 = 2 m (the tessellation has a vertex there).
  const float depth = img.depth[size_t(cy) * cam.width + cx];
  EXPECT_NEAR(depth, 2.0f, 0.02f);
  EXPECT_EQ(img.opaque_depth[size_t(cy) * cam.width + cx], depth);
  // Corners: sky, matching the CPU model to 16-bit float precision, at infinite depth.
  for (int c = 0; c < 4; ++c) {
    const int x = c & 1 ? cam.width - 1 : 0, y = c & 2 ? cam.height - 1 : 0;
    const Vec3f expected = scene.environment.sky(cam.ray(x + 0.5f, y + 0.5f).direction, true);
    EXPECT_LT(rel_diff(img.colour.at(x, y), expected), 0.01f) << "corner " << c;
    EXPECT_TRUE(std::isinf(img.depth[size_t(y) * cam.width + x]));
  }
  // Off-axis depth: the sphere point hit by a pixel's ray, projected on the view axis.
  const int x = cx + 20;
  const Ray r = cam.ray(x + 0.5f, cy + 0.5f);
  const float b = r.origin.dot(r.direction), t = -b - std::sqrt(b * b - (r.origin.squaredNorm() - 1.0f));
  EXPECT_NEAR(img.depth[size_t(cy) * cam.width + x], t * -r.direction.z(), 0.01f * t);
  // Lit towards the sun: the pixel whose normal faces the sun more is brighter.
  const Vec3f s = scene.environment.sun_direction;
  const int toward = s.x() > 0 ? cx + 30 : cx - 30, away = s.x() > 0 ? cx - 30 : cx + 30;
  EXPECT_GT(luminance(img.colour.at(toward, cy)), luminance(img.colour.at(away, cy)));
}

// A flat water body 1 m deep over a plain ground, seen from 2 m above it, sun behind the camera so no
// highlight lands in view: a closed slab, or just its top as a single quad (then rays leave the water
// where they meet the ground). Rows from the bottom (steep view) to the top (grazing).
struct FlatWater {
  TriangleMesh slab;
  Camera cam;
  SurfaceScene scene;
  explicit FlatWater(bool quad = false) {
    slab = quad ? make_quad_mesh(Vec3f(-60, 1, -60), Vec3f(0, 0, 120), Vec3f(120, 0, 0))
                : make_box_mesh(Vec3f(-60, 0, -60), Vec3f(60, 1, 60));
    cam.position = Vec3f(0, 3, 4), cam.target = Vec3f(0, 1, -6), cam.fov_y_degrees = 60;
    cam.width = 121, cam.height = 91;
    scene.fluid = &slab;
    scene.environment.sun_direction = Vec3f(0.0f, 0.5f, 1.0f).normalized();
    scene.environment.ground_tile = 0;  // plain, so the colour seen through the water is known
  }
  // Where the pixel's ray meets the water surface y = 1, and the cosine of its incidence angle.
  std::pair<Vec3f, float> hit(int x, int y) const {
    const Ray r = cam.ray(x + 0.5f, y + 0.5f);
    return {r.origin + r.direction * ((1.0f - r.origin.y()) / r.direction.y()), -r.direction.y()};
  }
  Vec3f reflected_sky(int x, int y) const {
    Vec3f d = cam.ray(x + 0.5f, y + 0.5f).direction;
    d.y() = -d.y();
    return scene.environment.sky(d, false);
  }
  float fresnel(float cos_i) const {
    const float n = scene.water.ior, f0 = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
    return f0 + (1 - f0) * std::pow(1 - cos_i, 5.0f);
  }
};

// Opaque water (huge absorption): what is seen is F * sky(reflected) + (1 - F) * deep colour, with
// Schlick's F growing from 0.02 at normal incidence towards 1 at grazing. Every sampled pixel must
// match that to 2% (16-bit float targets, normal interpolation on a flat face is exact).
TEST(GlSurfacePass, FlatWaterReflectsTheSkyWithSchlickFresnel) {
  for (bool quad : {false, true}) {
    SCOPED_TRACE(quad ? "quad" : "slab");
    FlatWater w(quad);
    w.scene.water.absorption = Vec3f::Constant(1e4f);
    w.scene.water.deep_color = Vec3f(0.01f, 0.04f, 0.06f);
    const SurfaceImage img = pass().render(w.scene, w.cam);
    save(img, "gl_water_fresnel.png");
    float previous = 0;
    for (int y = w.cam.height - 1; y >= w.cam.height / 2; y -= 5) {
      const int x = w.cam.width / 2;
      const auto [p, cos_i] = w.hit(x, y);
      const float f = w.fresnel(cos_i);
      const Vec3f expected = f * w.reflected_sky(x, y) + (1 - f) * w.scene.water.deep_color;
      EXPECT_LT(rel_diff(img.colour.at(x, y), expected), 0.02f) << "row " << y << ", cos " << cos_i;
      const float lum = luminance(img.colour.at(x, y));
      EXPECT_GT(lum, previous) << "brighter towards grazing, row " << y;
      previous = lum;
    }
  }
}

// Clear water, looking straight through (refraction off): the ground is seen through the path
// length L = 1 m / cos(angle) and absorbed per channel: exp(-sigma L) * ground + (1 - exp(-sigma L)) *
// deep colour. With sigma larger for red, sand under a metre of water reads blue-green.
TEST(GlSurfacePass, FlatWaterAbsorbsAlongThePathAndLooksBlue) {
  for (bool quad : {false, true}) {
    SCOPED_TRACE(quad ? "quad" : "slab");
    FlatWater w(quad);
    w.scene.water.refraction = 0;
    const SurfaceImage img = pass().render(w.scene, w.cam);
    save(img, "gl_water_absorption.png");
    const Environment& env = w.scene.environment;
    for (int y = w.cam.height - 1; y >= w.cam.height / 2; y -= 10) {
      const int x = w.cam.width / 2;
      const auto [p, cos_i] = w.hit(x, y);
      const Vec3f d = w.cam.ray(x + 0.5f, y + 0.5f).direction;
      const Vec3f bottom = p + d * (1.0f / cos_i);
      const Vec3f t = (-w.scene.water.absorption * (1.0f / cos_i)).array().exp();
      const Vec3f through = env.ground_radiance(bottom, w.cam.position).cwiseProduct(t) +
                            w.scene.water.deep_color.cwiseProduct(Vec3f::Ones() - t);
      const float f = w.fresnel(cos_i);
      const Vec3f expected = f * w.reflected_sky(x, y) + (1 - f) * through;
      EXPECT_LT(rel_diff(img.colour.at(x, y), expected), 0.02f) << "row " << y;
    }
    // Bluish where we look down into it, though the ground is sand (red > green > blue).
    const Vec3f c = img.colour.at(w.cam.width / 2, w.cam.height - 5);
    EXPECT_GT(c.z(), 1.2f * c.x());
    EXPECT_GT(c.y(), 1.2f * c.x());
    EXPECT_GT(env.ground_albedo.x(), env.ground_albedo.z());
  }
}

// A red wall standing behind opaque water: where the mirror ray of a pixel meets the wall, the water
// shows F * (the wall's radiance) + (1 - F) * deep colour (screen-space reflection finds the wall in
// the opaque image); with scene reflections off, the sky as before.
TEST(GlSurfacePass, FlatWaterReflectsASolidBehindIt) {
  FlatWater w(true);
  w.scene.water.absorption = Vec3f::Constant(1e4f);
  w.scene.water.deep_color = Vec3f(0.01f, 0.04f, 0.06f);
  const float wall_z = -7.5f;
  const TriangleMesh wall = make_box_mesh(Vec3f(-30, 0, -8), Vec3f(30, 6, wall_z));
  const Vec3f albedo(0.8f, 0.1f, 0.1f);
  w.scene.solids.push_back({&wall, albedo, Vec3f::Zero()});
  const Vec3f wall_radiance = albedo.cwiseProduct(w.scene.environment.irradiance(Vec3f::UnitZ())) / std::numbers::pi_v<float>;
  const SurfaceImage with = pass().render(w.scene, w.cam);
  save(with, "gl_water_reflects_wall.png");
  w.scene.water.scene_reflections = false;
  const SurfaceImage without = pass().render(w.scene, w.cam);
  int checked = 0;
  for (int y = w.cam.height - 1; y >= 0; --y) {
    const int x = w.cam.width / 2;
    const Ray r = w.cam.ray(x + 0.5f, y + 0.5f);
    if (r.direction.y() >= 0.0f) continue;
    const auto [p, cos_i] = w.hit(x, y);
    if (p.z() < wall_z + 0.5f) continue;  // the water in front of the wall only
    Vec3f d = r.direction;
    d.y() = -d.y();
    const Vec3f h = p + d * ((wall_z - p.z()) / d.z());
    if (h.y() < 1.3f || h.y() > 5.5f) continue;  // the mirror ray meets the wall well inside its face
    const float f = w.fresnel(cos_i);
    const Vec3f deep = w.scene.water.deep_color;
    EXPECT_LT(rel_diff(with.colour.at(x, y), f * wall_radiance + (1 - f) * deep), 0.03f) << "row " << y;
    EXPECT_LT(rel_diff(without.colour.at(x, y), f * w.reflected_sky(x, y) + (1 - f) * deep), 0.02f) << "row " << y;
    ++checked;
  }
  EXPECT_GT(checked, 5);
}

// With the default look (refraction on, sun in view): the sun's highlight shows on the water.
TEST(GlSurfacePass, SunHighlightOnWater) {
  FlatWater w;
  w.scene.environment.sun_direction = Vec3f(0.0f, 0.35f, -1.0f).normalized();  // ahead, low
  const SurfaceImage img = pass().render(w.scene, w.cam);
  save(img, "gl_water_sun.png");
  // The mirror direction of the sun seen in the water: brightest pixel of the centre column.
  float brightest = 0, median_like = 0;
  for (int y = w.cam.height / 2; y < w.cam.height; ++y) {
    const float lum = luminance(img.colour.at(w.cam.width / 2, y));
    brightest = std::max(brightest, lum);
    if (y == w.cam.height - 5) median_like = lum;
  }
  EXPECT_GT(brightest, 1.0f) << "a highlight brighter than white";
  EXPECT_LT(median_like, 0.3f);
}

TEST(GlSurfacePass, NoGeometryNoContext) {
  SurfacePass fresh(SurfacePassOptions{.supersample = 1, .gl = {}});
  SurfaceScene scene;
  Camera cam = sphere_camera();
  cam.position = Vec3f(0, 2, 3), cam.target = Vec3f(0, 2, 0);  // level: sky above, ground below
  SurfacePassStats stats;
  const SurfaceImage img = fresh.render(scene, cam, &stats);
  EXPECT_FALSE(stats.used_gl);
  EXPECT_FALSE(fresh.has_context());
  EXPECT_EQ(img.colour.width, cam.width);
  EXPECT_TRUE(std::isfinite(img.depth.back())) << "ground at the bottom";
  EXPECT_TRUE(std::isinf(img.depth.front())) << "sky at the top";
}

// The GLSL and C++ versions of the environment agree: a scene whose only solid is behind the camera
// goes through GL and must match the CPU background (sky and ground) to 16-bit float precision,
// away from the checker's edges.
TEST(GlSurfacePass, GlAndCpuEnvironmentsAgree) {
  const TriangleMesh box = make_box_mesh(Vec3f(-1, 0, 10), Vec3f(1, 1, 11));
  SurfaceScene scene;
  scene.solids.push_back({&box, Vec3f::Ones(), Vec3f::Zero()});
  scene.environment.ground_tile = 0;
  Camera cam = sphere_camera();
  cam.position = Vec3f(0, 2, 3), cam.target = Vec3f(0, 1.5f, 0);
  const SurfaceImage gl = pass().render(scene, cam), cpu = render_background(scene.environment, cam);
  size_t bad = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      if (rel_diff(gl.colour.at(x, y), cpu.colour.at(x, y)) > 0.01f) ++bad;
      const float a = gl.depth[size_t(y) * cam.width + x], b = cpu.depth[size_t(y) * cam.width + x];
      if (std::isinf(a) != std::isinf(b) || (!std::isinf(a) && std::abs(a - b) > 1e-3f * b)) ++bad;
    }
  EXPECT_LE(bad, size_t(cam.width) * 2) << "allow the horizon row";
}

// One context serves frames of different sizes.
TEST(GlSurfacePass, ContextIsReusedAcrossSizes) {
  const TriangleMesh sphere = make_sphere_mesh(Vec3f::Zero(), 1.0f);
  SurfaceScene scene;
  scene.solids.push_back({&sphere, Vec3f::Ones(), Vec3f::Zero()});
  Camera cam = sphere_camera();
  for (int w : {64, 200, 64}) {
    cam.width = w, cam.height = w / 2 + 1;
    const SurfaceImage img = pass().render(scene, cam);
    EXPECT_EQ(img.colour.width, w);
    EXPECT_EQ(img.depth.size(), size_t(w) * (w / 2 + 1));
  }
  EXPECT_TRUE(pass().has_context());
}

}  // namespace
}  // namespace spume

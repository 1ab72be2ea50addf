#include "render/frame/frame_layers.h"

#include <cmath>
#include <numbers>

#include "sim/core/error.h"

namespace spume {
namespace {

Rgba opaque_pixel(const Vec3f& c) { return {c.x(), c.y(), c.z(), 1.0f}; }

Rgba over(const Rgba& front, const Rgba& back) {
  const float t = 1.0f - front[3];
  return {front[0] + t * back[0], front[1] + t * back[1], front[2] + t * back[2], front[3] + t * back[3]};
}

}  // namespace

const RgbaLayer* FrameLayers::layer(const std::string& name) const {
  for (const RgbaLayer& l : layers)
    if (l.name == name) return &l;
  return nullptr;
}

FrameLayers frame_layers(const ImageRGBf& beauty, const SurfaceImage& surface, const VolumeImage* volume,
                         const std::array<bool, kDiffuseTypeCount>& drawn, const Camera& camera) {
  const size_t n = beauty.pixel_count();
  if (surface.colour.pixel_count() != n || surface.opaque_colour.pixel_count() != n || surface.depth.size() != n ||
      surface.opaque_depth.size() != n || (volume && volume->transmittance.size() != n))
    fail("frame layers: the passes' images differ in size from the frame's ", beauty.width, "x", beauty.height);
  FrameLayers f;
  f.width = beauty.width, f.height = beauty.height;
  f.beauty.resize(n);
  f.distance.resize(n);
  RgbaLayer sky{"sky", std::vector<Rgba>(n)}, opaque{"opaque", std::vector<Rgba>(n)}, water{"water", std::vector<Rgba>(n)};
  // Planar depth -> distance: the unnormalised ray through a pixel has a forward component of 1.
  const float tan_half = std::tan(0.5f * camera.fov_y_degrees * std::numbers::pi_v<float> / 180.0f);
  const float aspect = float(camera.width) / float(camera.height);
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const size_t p = size_t(y) * size_t(f.width) + size_t(x);
      f.beauty[p] = opaque_pixel(beauty.rgb[p]);
      const float sx = (2.0f * (float(x) + 0.5f) / float(camera.width) - 1.0f) * tan_half * aspect;
      const float sy = (1.0f - 2.0f * (float(y) + 0.5f) / float(camera.height)) * tan_half;
      const float depth = surface.depth[p];
      f.distance[p] = std::isfinite(depth) ? depth * std::sqrt(sx * sx + sy * sy + 1.0f) : FrameLayers::kSkyDistance;
      // Where pass 1 drew nothing the sky shows; where the water is nearer than it, the water does.
      (std::isfinite(surface.opaque_depth[p]) ? opaque : sky).pixels[p] = opaque_pixel(surface.opaque_colour.rgb[p]);
      if (depth < surface.opaque_depth[p]) water.pixels[p] = opaque_pixel(surface.colour.rgb[p]);
    }
  f.layers.push_back(std::move(sky));
  f.layers.push_back(std::move(opaque));
  f.layers.push_back(std::move(water));
  for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k) {
    if (!drawn[k]) continue;
    RgbaLayer l{to_string(DiffuseType(k)), std::vector<Rgba>(n, Rgba{0, 0, 0, 0})};
    if (volume && volume->type_opacity[k].size() == n)
      for (size_t p = 0; p < n; ++p) {
        const Vec3f& c = volume->type_premultiplied[k][p];
        l.pixels[p] = {c.x(), c.y(), c.z(), volume->type_opacity[k][p]};
      }
    f.layers.push_back(std::move(l));
  }
  return f;
}

std::vector<Rgba> recomposite(const FrameLayers& f) {
  const size_t n = f.beauty.size();
  std::vector<Rgba> out(n, Rgba{0, 0, 0, 0});
  for (size_t p = 0; p < n; ++p) {
    Rgba diffuse{0, 0, 0, 0};
    for (size_t i = 3; i < f.layers.size(); ++i)
      for (int c = 0; c < 4; ++c) diffuse[size_t(c)] += f.layers[i].pixels[p][size_t(c)];
    out[p] = over(diffuse, over(f.layers[2].pixels[p], over(f.layers[1].pixels[p], f.layers[0].pixels[p])));
  }
  return out;
}

}  // namespace spume

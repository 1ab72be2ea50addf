#pragma once
// A frame taken apart for compositing (the EXR frames, render/image/exr_io.h). All linear RGB, RGBA
// premultiplied, rows top to bottom:
//   beauty  the picture the PNG shows, before sRGB encoding; A = 1 (the sky is drawn)
//   sky     the sky where no ground or solid lies along the pixel (A = 1 there, else 0)
//   opaque  the ground and solids as the surface pass draws them before the water (A = 1 where they are)
//   water   the shaded water where it is seen, refraction of what lies below included (A = 1 there)
//   spray, foam, bubble (drawn types only)  each type's own part of Eq. 9: opacity (1 - L) s_k and
//           colour (1 - L) s_k C_k, where s_k is the type's share of the optical depth along the
//           ray (absorption.h); over the types they sum to 1 - L and (1 - L) C_d
// Beauty = (spray + foam + bubble) over water over opaque over sky: the diffuse layers add (their sum
// is Eq. 9's composite with alpha 1 - L), the rest stack with `over`. Exact in float; the EXR's half
// floats round each term to 2^-11 of its size.
//   distance  Z: m from the camera to the first ground, solid or water surface; kSkyDistance for sky.
//   motion    screen-space motion vectors, pixels per frame (motion_vectors.h)
#include <array>
#include <string>
#include <vector>

#include "render/camera/camera.h"
#include "render/gl/surface_pass.h"
#include "render/volume/volume_types.h"

namespace spume {

using Rgba = std::array<float, 4>;

struct RgbaLayer {
  std::string name;
  std::vector<Rgba> pixels;
};

struct FrameLayers {
  // Large and finite: compositing tools read it as "far", and it survives arithmetic that inf would not.
  static constexpr float kSkyDistance = 1e10f;

  int width = 0, height = 0;
  std::vector<Rgba> beauty;
  std::vector<float> distance;
  std::vector<RgbaLayer> layers;  // in the order above
  std::vector<Rgba> motion;       // forward u, v and backward u, v (motion_vectors.h); empty: none

  const RgbaLayer* layer(const std::string& name) const;
};

// `beauty`: the composited frame; `surface` with opaque_colour; `volume` with split_types, or null when
// no volume pass ran (the diffuse layers are then empty). `drawn`: the diffuse types that get a layer.
FrameLayers frame_layers(const ImageRGBf& beauty, const SurfaceImage& surface, const VolumeImage* volume,
                         const std::array<bool, kDiffuseTypeCount>& drawn, const Camera& camera);

// The layers put back together as the header says (beauty from its parts), for tests and checks.
std::vector<Rgba> recomposite(const FrameLayers& frame);

}  // namespace spume

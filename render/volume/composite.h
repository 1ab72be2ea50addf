#pragma once
// Eq. 9's compositing step: C_p = (1 - L) C_d + L C_b, in linear RGB.
#include "render/image/image.h"
#include "render/volume/volume_types.h"

namespace spume {

inline Vec3f composite(float transmittance, const Vec3f& diffuse, const Vec3f& background) {
  return (1.0f - transmittance) * diffuse + transmittance * background;
}

// Over a background image of the same size (the OSMesa render, decoded to linear). Throws Error
// when the sizes differ.
ImageRGBf composite(const VolumeImage& volume, const ImageRGBf& background);
// Over a constant colour (tests, look-dev swatches).
ImageRGBf composite(const VolumeImage& volume, const Vec3f& background);

}  // namespace spume

#include "render/volume/composite.h"

#include "sim/core/error.h"

namespace spume {

ImageRGBf composite(const VolumeImage& volume, const ImageRGBf& background) {
  if (volume.width != background.width || volume.height != background.height)
    fail("composite: volume image is ", volume.width, "x", volume.height, " but background is ", background.width, "x",
         background.height);
  ImageRGBf out(volume.width, volume.height);
  for (size_t i = 0; i < out.pixel_count(); ++i)
    out.rgb[i] = composite(volume.transmittance[i], volume.color[i], background.rgb[i]);
  return out;
}

ImageRGBf composite(const VolumeImage& volume, const Vec3f& background) {
  ImageRGBf out(volume.width, volume.height);
  for (size_t i = 0; i < out.pixel_count(); ++i) out.rgb[i] = composite(volume.transmittance[i], volume.color[i], background);
  return out;
}

}  // namespace spume

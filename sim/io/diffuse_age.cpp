#include "sim/io/diffuse_age.h"

#include "sim/core/error.h"

namespace spume {

std::vector<float> diffuse_ages(const DiffuseFrame& frame, int substeps, double fps) {
  if (substeps < 1 || !(fps > 0.0)) fail("diffuse ages: substeps ", substeps, " and fps ", fps, " must be positive");
  const int64_t now = int64_t(frame.index) * substeps;
  const double step = 1.0 / (fps * substeps);
  std::vector<float> ages(frame.size());
  for (size_t i = 0; i < ages.size(); ++i) {
    const int64_t born = diffuse_id_step(frame.ids[i]);
    if (born > now)
      fail("frame ", frame.index, ": diffuse particle ", frame.ids[i], " was born in step ", born, ", after this frame's step ",
           now, " (", substeps, " substeps a frame): the cache was not made with these keys");
    ages[i] = float(double(now - born) * step);
  }
  return ages;
}

}  // namespace spume

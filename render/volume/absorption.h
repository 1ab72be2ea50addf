#pragma once
// From what one eye ray meets to its transmittance L and diffuse colour C_d.
//
// L = exp(-alpha * length inside the union of all drawn spheres) (exact) or the product of Eq. 9's
// factors (march). C_d where types mix along a ray is the optical-depth-weighted mix of the type
// colours: C_d = sum_k tau_k C_k / sum_k tau_k with tau_k = alpha * (length inside type k's
// spheres); where spheres of two types overlap the length counts for both. Material seen through
// water adds exp(-sigma_w w(t)) tau_k C_k instead (w = distance travelled in water), so it darkens
// and takes the water's tint while its opacity, and L, stay as Eq. 9 says.
#include <array>
#include <cstddef>

#include "sim/core/frames.h"
#include "render/volume/ray_sphere.h"
#include "render/volume/water_path.h"

namespace spume {

struct VolumeShading {
  double alpha = 0.0;                             // 1/m
  std::array<Vec3d, kDiffuseTypeCount> color{};   // linear RGB per type
  Vec3d water_sigma = Vec3d::Zero();              // 1/m per channel
};

struct RaySample {
  double transmittance = 1.0;
  Vec3d color = Vec3d::Zero();
};

// Each type's part of a RaySample, for the per-type layers, made only when asked for (a pointer that
// may be null below): share[k] = tau_k / sum_j tau_j (the share of the opacity 1 - L it owns; they
// sum to 1 where anything is seen) and type_color[k] its term of `color` (they sum to it, to rounding).
struct RayTypes {
  std::array<double, kDiffuseTypeCount> share{};
  std::array<Vec3d, kDiffuseTypeCount> type_color{Vec3d::Zero(), Vec3d::Zero(), Vec3d::Zero()};
};

// The colour from per-type lengths inside the material and the same lengths dimmed by the water in
// front (weight), into out.color and, when not null, *types.
void mix_color(const VolumeShading& shading, const std::array<double, kDiffuseTypeCount>& length,
               const std::array<Vec3d, kDiffuseTypeCount>& weight, RaySample& out, RayTypes* types);

// The water stretches of one ray (empty when it never enters water).
struct WaterView {
  const WaterSegment* seg = nullptr;
  size_t n = 0;
};

// Order of chords: by t0, then t1, then type.
inline bool interval_before(const Interval& a, const Interval& b) {
  if (a.t0 != b.t0) return a.t0 < b.t0;
  if (a.t1 != b.t1) return a.t1 < b.t1;
  return a.type < b.type;
}

// Sorts by interval_before with insertion sort: the screen-bin method feeds spheres in
// depth order, so chords arrive almost sorted and this costs about one pass.
void sort_intervals(Interval* iv, size_t n);

// Chords sorted by t0 (sort_intervals). Lengths summed in double, in t order: deterministic.
RaySample absorb_intervals(const Interval* iv, size_t n, const VolumeShading& shading, WaterView water,
                           RayTypes* types = nullptr);

// Eq. 9 as written: add() one sample x_s + i dx w per i, with the set of types whose spheres
// contain it (bit k = type k) and its distance t along the ray (for water dimming).
class MarchAccumulator {
 public:
  MarchAccumulator(const VolumeShading& shading, WaterView water, double dx) : shading_(shading), water_(water), dx_(dx) {}
  void add(unsigned type_mask, double t);
  RaySample finish(RayTypes* types = nullptr) const;

 private:
  const VolumeShading& shading_;
  WaterView water_;
  double dx_;
  size_t covered_ = 0;  // samples with delta = 1
  std::array<double, kDiffuseTypeCount> length_{};
  std::array<Vec3d, kDiffuseTypeCount> weight_{Vec3d::Zero(), Vec3d::Zero(), Vec3d::Zero()};
};

// Averages the samples of one pixel so that compositing the average over a constant background
// equals averaging the composited samples: L = mean L_s, C_d = mean((1 - L_s) C_s) / (1 - L).
// Per type, when asked: opacity_k = mean((1 - L_s) share_k), premultiplied_k = mean((1 - L_s)
// type_color_k), which sum over k to 1 - L and (1 - L) C_d.
class PixelAverage {
 public:
  explicit PixelAverage(bool by_type = false) : by_type_(by_type) {}
  void add(const RaySample& s, const RayTypes* types = nullptr) {
    const double opacity = 1.0 - s.transmittance;
    l_sum_ += s.transmittance;
    premultiplied_ += opacity * s.color;
    if (by_type_ && types)
      for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k) {
        type_opacity_[k] += opacity * types->share[k];
        type_premultiplied_[k] += opacity * types->type_color[k];
      }
    ++n_;
  }
  void finish(float& transmittance, Vec3f& color) const;
  // Type k's premultiplied colour and opacity (0 without samples or by_type).
  void finish_type(size_t k, Vec3f& premultiplied, float& opacity) const;

 private:
  bool by_type_;
  double l_sum_ = 0.0;
  Vec3d premultiplied_ = Vec3d::Zero();
  std::array<double, kDiffuseTypeCount> type_opacity_{};
  std::array<Vec3d, kDiffuseTypeCount> type_premultiplied_{Vec3d::Zero(), Vec3d::Zero(), Vec3d::Zero()};
  int n_ = 0;
};

}  // namespace spume

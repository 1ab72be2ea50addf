#include "render/volume/absorption.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <emmintrin.h>

namespace spume {

void mix_color(const VolumeShading& shading, const std::array<double, kDiffuseTypeCount>& length,
               const std::array<Vec3d, kDiffuseTypeCount>& weight, RaySample& out, RayTypes* types) {
  double total = 0.0;
  Vec3d c = Vec3d::Zero();
  for (int k = 0; k < kDiffuseTypeCount; ++k) {
    total += length[size_t(k)];
    c += shading.color[size_t(k)].cwiseProduct(weight[size_t(k)]);
  }
  if (!(total > 0.0)) return;
  out.color = c / total;
  if (!types) return;
  for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k) {
    types->share[k] = length[k] / total;
    types->type_color[k] = shading.color[k].cwiseProduct(weight[k]) / total;
  }
}

void sort_intervals(Interval* iv, size_t n) {
  for (size_t i = 1; i < n; ++i) {
    if (!interval_before(iv[i], iv[i - 1])) continue;
    const Interval x = iv[i];
    size_t j = i;
    for (; j > 0 && interval_before(x, iv[j - 1]); --j) iv[j] = iv[j - 1];
    iv[j] = x;
  }
}

namespace {
// One pass over chords sorted by t0, merging those of `type` (all types when type < 0) into
// disjoint components; on_component(t0, t1) sees each component once, in t order. Touching chords
// merge or not, the length is the same. Returns the total length.
template <typename OnComponent>
double sweep_union(const Interval* iv, size_t n, int type, OnComponent&& on_component) {
  double total = 0.0, s = 0.0, e = -INFINITY;
  bool open = false;
  for (size_t i = 0; i < n; ++i) {
    if (type >= 0 && iv[i].type != uint32_t(type)) continue;
    const double t0 = iv[i].t0, t1 = iv[i].t1;
    if (open && t0 <= e) {
      e = std::max(e, t1);
      continue;
    }
    if (open) total += e - s, on_component(s, e);
    s = t0, e = t1, open = true;
  }
  if (open) total += e - s, on_component(s, e);
  return total;
}

// sweep_union(iv, n, -1, no-op) without a branch per chord, for the common ray: no water, one
// type (the branch mispredicted at every gap between components). The same sums in the same
// order, so the same bits: a component's length e - s is recorded when the next chord starts a
// new one (a slot written every chord, kept when gap), and the lengths are added in order after
// each block of chords, so the running total is not a dependency of every chord. The end e is
// max(e, t1) at every chord: when a new component starts, t1 >= t0 > e, so that is t1.
// std::max(e, t1) is _mm_max_sd(t1, e).
double union_length_all(const Interval* iv, size_t n) {
  constexpr size_t kBlock = 64;
  double length[kBlock];
  double total = 0.0;
  __m128d s = _mm_set_sd(iv[0].t0), e = _mm_set_sd(iv[0].t1);
  for (size_t b = 1; b < n; b += kBlock) {
    size_t k = 0;
    for (size_t i = b, end = std::min(n, b + kBlock); i < end; ++i) {
      const __m128d t0 = _mm_set_sd(iv[i].t0), t1 = _mm_set_sd(iv[i].t1);
      const __m128d gap = _mm_cmpgt_sd(t0, e);
      length[k] = _mm_cvtsd_f64(_mm_sub_sd(e, s));
      k += size_t(_mm_movemask_pd(gap) & 1);
      s = _mm_or_pd(_mm_and_pd(gap, t0), _mm_andnot_pd(gap, s));
      e = _mm_max_sd(t1, e);
    }
    for (size_t j = 0; j < k; ++j) total += length[j];
  }
  return total + _mm_cvtsd_f64(_mm_sub_sd(e, s));
}
}  // namespace

RaySample absorb_intervals(const Interval* iv, size_t n, const VolumeShading& shading, WaterView water,
                           RayTypes* types) {
  RaySample out;
  if (n == 0) return out;
  unsigned seen = 0;
  for (size_t i = 0; i < n; ++i) seen |= 1u << iv[i].type;
  std::array<double, kDiffuseTypeCount> length{};
  std::array<Vec3d, kDiffuseTypeCount> weight{Vec3d::Zero(), Vec3d::Zero(), Vec3d::Zero()};
  auto per_type = [&](size_t k, int filter) {
    Vec3d& w = weight[k];
    length[k] = water.n ? sweep_union(iv, n, filter, [&](double a, double b) { w += dimmed_length(water.seg, water.n, shading.water_sigma, a, b); })
                        : sweep_union(iv, n, filter, [](double, double) {});
    if (!water.n) w = Vec3d::Constant(length[k]);
    return length[k];
  };
  double union_length;
  if ((seen & (seen - 1)) == 0 && !water.n) {
    const size_t k = size_t(std::countr_zero(seen));
    union_length = length[k] = union_length_all(iv, n);
    weight[k] = Vec3d::Constant(length[k]);
  } else if ((seen & (seen - 1)) == 0) {  // one type along this ray, the common case: one pass does all
    union_length = per_type(size_t(std::countr_zero(seen)), -1);
  } else {
    union_length = sweep_union(iv, n, -1, [](double, double) {});
    for (int k = 0; k < kDiffuseTypeCount; ++k)
      if (seen & (1u << k)) per_type(size_t(k), k);
  }
  out.transmittance = std::exp(-shading.alpha * union_length);
  mix_color(shading, length, weight, out, types);
  return out;
}

void MarchAccumulator::add(unsigned type_mask, double t) {
  if (type_mask == 0) return;
  ++covered_;
  Vec3d dim = Vec3d::Ones();
  if (water_.n) {
    const double w = water_distance(water_.seg, water_.n, t);
    for (int c = 0; c < 3; ++c) dim[c] = std::exp(-shading_.water_sigma[c] * w);
  }
  for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k)
    if (type_mask & (1u << k)) {
      length_[k] += dx_;
      weight_[k] += dx_ * dim;
    }
}

RaySample MarchAccumulator::finish(RayTypes* types) const {
  RaySample out;
  // prod_i exp(-delta_i alpha dx) = exp(-alpha dx * #{i : delta_i = 1}): the same product, without
  // rounding a long chain of factors.
  out.transmittance = std::exp(-shading_.alpha * dx_ * double(covered_));
  mix_color(shading_, length_, weight_, out, types);
  return out;
}

void PixelAverage::finish(float& transmittance, Vec3f& color) const {
  if (n_ == 0) {
    transmittance = 1.0f, color = Vec3f::Zero();
    return;
  }
  const double l = l_sum_ / n_, opacity = 1.0 - l;
  transmittance = float(l);
  color = opacity > 0.0 ? Vec3f((premultiplied_ / (n_ * opacity)).cast<float>()) : Vec3f::Zero();
}

void PixelAverage::finish_type(size_t k, Vec3f& premultiplied, float& opacity) const {
  if (n_ == 0 || !by_type_) {
    premultiplied = Vec3f::Zero(), opacity = 0.0f;
    return;
  }
  premultiplied = (type_premultiplied_[k] / n_).cast<float>();
  opacity = float(type_opacity_[k] / n_);
}

}  // namespace spume

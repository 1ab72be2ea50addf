#pragma once
// A 3-vector padded to four floats, for the pressure iterations' neighbour loops: one SSE2 operation
// does the x, y and z of a pair at once, each lane the very IEEE operation the scalar code does on
// that component, so results keep every bit (the fourth lane is 0 and never read back). Without SSE2 the
// same operations run on plain floats.
#include <cstdint>
#include <vector>

#include "sim/core/vec.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace spume::fluid {

struct alignas(16) Padded3 {
  float c[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  Padded3() = default;
  explicit Padded3(const Vec3f& v) : c{v.x(), v.y(), v.z(), 0.0f} {}
  Vec3f vec() const { return Vec3f(c[0], c[1], c[2]); }
};

#if defined(__SSE2__)
struct Lanes {
  __m128 m;
  static Lanes load(const Padded3& p) { return {_mm_load_ps(p.c)}; }
  static Lanes of(const Vec3f& v) { return {_mm_setr_ps(v.x(), v.y(), v.z(), 0.0f)}; }
  static Lanes with_w(const Padded3& p, float w) { return {_mm_setr_ps(p.c[0], p.c[1], p.c[2], w)}; }
  Lanes broadcast_w() const { return {_mm_shuffle_ps(m, m, _MM_SHUFFLE(3, 3, 3, 3))}; }
  Lanes xyz() const { return {_mm_and_ps(m, _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)))}; }  // w = 0
  static Lanes splat(float s) { return {_mm_set1_ps(s)}; }
  static Lanes zero() { return {_mm_setzero_ps()}; }
  void store(Padded3& p) const { _mm_store_ps(p.c, m); }
  friend Lanes operator+(Lanes a, Lanes b) { return {_mm_add_ps(a.m, b.m)}; }
  friend Lanes operator-(Lanes a, Lanes b) { return {_mm_sub_ps(a.m, b.m)}; }
  friend Lanes operator*(Lanes a, Lanes b) { return {_mm_mul_ps(a.m, b.m)}; }
  // (x + y) + z, the order of the scalar expression a.x * b.x + a.y * b.y + a.z * b.z.
  float sum3() const {
    const __m128 y = _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 1, 1, 1));
    const __m128 z = _mm_movehl_ps(m, m);
    return _mm_cvtss_f32(_mm_add_ss(_mm_add_ss(m, y), z));
  }
};
#else
struct Lanes {
  float m[4];
  static Lanes load(const Padded3& p) { return {{p.c[0], p.c[1], p.c[2], p.c[3]}}; }
  static Lanes of(const Vec3f& v) { return {{v.x(), v.y(), v.z(), 0.0f}}; }
  static Lanes with_w(const Padded3& p, float w) { return {{p.c[0], p.c[1], p.c[2], w}}; }
  Lanes broadcast_w() const { return splat(m[3]); }
  Lanes xyz() const { return {{m[0], m[1], m[2], 0.0f}}; }
  static Lanes splat(float s) { return {{s, s, s, s}}; }
  static Lanes zero() { return splat(0.0f); }
  void store(Padded3& p) const {
    for (int l = 0; l < 4; ++l) p.c[l] = m[l];
  }
  friend Lanes operator+(Lanes a, Lanes b) { return {{a.m[0] + b.m[0], a.m[1] + b.m[1], a.m[2] + b.m[2], a.m[3] + b.m[3]}}; }
  friend Lanes operator-(Lanes a, Lanes b) { return {{a.m[0] - b.m[0], a.m[1] - b.m[1], a.m[2] - b.m[2], a.m[3] - b.m[3]}}; }
  friend Lanes operator*(Lanes a, Lanes b) { return {{a.m[0] * b.m[0], a.m[1] * b.m[1], a.m[2] * b.m[2], a.m[3] * b.m[3]}}; }
  float sum3() const { return (m[0] + m[1]) + m[2]; }
};
#endif

// A sum over a particle's pairs kept as kPartialSums independent vector sums: pair k (counted from the
// first) goes to sum k mod kPartialSums, and the sums are added in a fixed order at the end. One
// running sum makes every pair wait for the previous pair's addition (about 4 cycles); four keep the
// adder busy. The result depends only on the pairs and their order, never on threads.
constexpr uint32_t kPartialSums = 4;

struct PartialSums {
  Lanes s[kPartialSums] = {Lanes::zero(), Lanes::zero(), Lanes::zero(), Lanes::zero()};

  // Adds term(k) for k in [begin, end).
  template <typename Term>
  void add_pairs(uint32_t begin, uint32_t end, Term&& term) {
    uint32_t k = begin;
    for (; k + kPartialSums <= end; k += kPartialSums) {
      s[0] = s[0] + term(k);
      s[1] = s[1] + term(k + 1);
      s[2] = s[2] + term(k + 2);
      s[3] = s[3] + term(k + 3);
    }
    if (k < end) s[0] = s[0] + term(k++);
    if (k < end) s[1] = s[1] + term(k++);
    if (k < end) s[2] = s[2] + term(k);
  }
  Lanes total() const { return (s[0] + s[1]) + (s[2] + s[3]); }
};

}  // namespace spume::fluid

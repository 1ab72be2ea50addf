#include "sim/io/diffuse_packing.h"

#include <algorithm>

#include "sim/io/diffuse_quantized.h"

namespace spume {
namespace {

// round(x) (half away from zero) clamped to [lo, hi], for integers lo and hi within int32. Clamping
// before the truncation gives the same integer as after it (a value past an integer bound truncates to
// that bound or beyond), and keeps the conversion within 32 bits, which vectorizes.
inline int32_t rounded_within(double x, double lo, double hi) {
  const double t = x + (x >= 0.0 ? 0.5 : -0.5);
  return int32_t(t < lo ? lo : (t > hi ? hi : t));
}

struct QuantizedBlock {
  int32_t steps[3][kPackBlock], velocity[3][kPackBlock], life[kPackBlock];
};

// The arithmetic runs over plain arrays (x y z per particle), which the compiler vectorizes with the
// same IEEE operations at any width, inlined into the two entry points below, each built for AVX2 and
// baseline x86-64 and picked at load time: at 15M particles the quantization took 6.5% of a frame's
// CPU time scalar.
inline void quantize_positions(const float* position, size_t m, const PackingSteps& q, QuantizedBlock& out) {
  for (int a = 0; a < 3; ++a) {
    const double origin = q.origin[a], per_step = q.per_step, max_steps = q.max_steps[a];
    for (size_t j = 0; j < m; ++j)
      out.steps[a][j] = rounded_within((double(position[3 * j + a]) - origin) * per_step, 0.0, max_steps);
  }
}

inline void quantize_motion(const float* velocity, const float* lifetime, size_t m, const PackingSteps& q,
                            QuantizedBlock& out) {
  const double per_velocity_step = q.per_velocity_step;
  for (int a = 0; a < 3; ++a)
    for (size_t j = 0; j < m; ++j)
      out.velocity[a][j] = rounded_within(double(velocity[3 * j + a]) * per_velocity_step, -32767.0, 32767.0);
  for (size_t j = 0; j < m; ++j)
    out.life[j] = rounded_within((double(lifetime[j]) - q.life_origin) * q.per_life_step, 0.0, 65535.0);
}

// Positions of m consecutive particles.
__attribute__((target_clones("avx2", "default"))) void quantize_run(const float* position, size_t m,
                                                                     const PackingSteps& q, QuantizedBlock& out) {
  quantize_positions(position, m, q, out);
}

// Particles index[0..m) gathered into plain arrays first, so the arithmetic runs as over the frame's
// own (a running simulation keeps its particles in cell order: the gather is mostly local).
__attribute__((target_clones("avx2", "default"))) void quantize_gathered(const DiffuseFrame& frame,
                                                                          const uint32_t* index, size_t m,
                                                                          const PackingSteps& q,
                                                                          QuantizedBlock& out) {
  float position[3 * kPackBlock], velocity[3 * kPackBlock], lifetime[kPackBlock];
  constexpr size_t kAhead = 16;  // particles: their loads are issued while earlier ones are copied
  for (size_t j = 0; j < m; ++j) {
    if (j + kAhead < m) {
      const uint32_t ahead = index[j + kAhead];
      __builtin_prefetch(&frame.positions[ahead]), __builtin_prefetch(&frame.velocities[ahead]);
      __builtin_prefetch(&frame.lifetimes[ahead]), __builtin_prefetch(&frame.ids[ahead]);
      __builtin_prefetch(&frame.types[ahead]);
    }
    const uint32_t i = index[j];
    for (int a = 0; a < 3; ++a) position[3 * j + a] = frame.positions[i][a], velocity[3 * j + a] = frame.velocities[i][a];
    lifetime[j] = frame.lifetimes[i];
  }
  quantize_positions(position, m, q, out);
  quantize_motion(velocity, lifetime, m, q, out);
}

uint64_t key_of(const QuantizedBlock& b, size_t j, const std::array<uint32_t, 3>& cells) {
  uint64_t cell[3];
  for (int a = 0; a < 3; ++a) cell[a] = uint64_t(b.steps[a][j]) >> kCellOffsetBits;
  return cell[0] + cells[0] * (cell[1] + uint64_t(cells[1]) * cell[2]);
}

}  // namespace

void cell_keys(const DiffuseFrame& frame, const PackingSteps& q, size_t begin, size_t end, uint64_t* keys,
               bool with_index) {
  QuantizedBlock block;
  for (size_t b = begin; b < end; b += kPackBlock) {
    const size_t m = std::min(kPackBlock, end - b);
    quantize_run(frame.positions[b].data(), m, q, block);
    for (size_t j = 0; j < m; ++j) {
      const uint64_t key = key_of(block, j, q.cells);
      keys[b + j] = with_index ? key << 32 | (b + j) : key;
    }
  }
}

void pack_sorted_block(const DiffuseFrame& frame, const PackingSteps& q, const uint32_t* index, size_t m,
                       size_t first, QuantizedDiffuse& out) {
  constexpr uint32_t kOffsetMask = (1u << kCellOffsetBits) - 1;
  QuantizedBlock block;
  quantize_gathered(frame, index, m, q, block);
  const size_t n = out.size();
  for (int a = 0; a < 3; ++a)
    for (size_t j = 0; j < m; ++j) {
      out.offsets[a * n + first + j] = uint8_t(uint32_t(block.steps[a][j]) & kOffsetMask);
      out.velocities[a * n + first + j] = int16_t(block.velocity[a][j]);
    }
  for (size_t j = 0; j < m; ++j) {
    out.lifetimes[first + j] = uint16_t(block.life[j]);
    out.ids[first + j] = frame.ids[index[j]];
  }
  for (size_t j = 0; j < m; j += 4) {
    uint8_t types = 0;
    for (size_t t = j; t < std::min(m, j + 4); ++t) types |= uint8_t(uint8_t(frame.types[index[t]]) << (2 * (t % 4)));
    out.types[(first + j) / 4] = types;
  }
}

}  // namespace spume

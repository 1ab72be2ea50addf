#pragma once
// The per-particle steps of quantize_diffuse (diffuse_quantized.h): each particle's cell key, in the
// frame's order, and the quantized columns, in the cell order.
#include <array>
#include <cstddef>
#include <cstdint>

#include "sim/core/frames.h"

namespace spume {

struct QuantizedDiffuse;

// The frame's quantization as multipliers (see diffuse_quantized.h for the rules).
struct PackingSteps {
  std::array<double, 3> origin{};     // m
  std::array<double, 3> max_steps{};  // the largest step count along each axis, an integer below 2^31
  double per_step = 0.0;              // 1 / position step
  double per_velocity_step = 0.0;     // 1 / velocity step, 0 when all velocities are 0
  double life_origin = 0.0;
  double per_life_step = 0.0;         // 1 / life step, 0 when all lifetimes are equal
  std::array<uint32_t, 3> cells{};    // cells per axis
};

// The cell keys of particles [begin, end), into keys[begin, end): with_index (a frame of at most 2^32
// cells) as key << 32 | particle index, the pair the cell sort moves; otherwise the key alone.
void cell_keys(const DiffuseFrame& frame, const PackingSteps& steps, size_t begin, size_t end, uint64_t* keys,
               bool with_index);

constexpr size_t kPackBlock = 256;  // sorted slots a pack_sorted_block call fills at most

// The quantized columns of sorted slots [first, first + m), m <= kPackBlock, slot first + j holding
// particle index[j] of the frame. `first` is a multiple of 4 and so is m but at the end, so that each
// byte of 4 types belongs to one call. out's columns are sized for the frame.
void pack_sorted_block(const DiffuseFrame& frame, const PackingSteps& steps, const uint32_t* index, size_t m,
                       size_t first, QuantizedDiffuse& out);

}  // namespace spume

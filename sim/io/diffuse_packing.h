#pragma once
// The per-particle step of quantize_diffuse (diffuse_quantized.h): each particle's quantized values
// and cell key, packed in a record the cell sort moves whole.
#include <array>
#include <cstddef>
#include <cstdint>

#include "sim/core/frames.h"

namespace spume {

// One particle quantized, with its cell key when the frame has at most 2^32 cells: 24 bytes that the
// sort moves whole, so that no pass reads the frame at random (a frame's particles away from the
// fluid come in no spatial order).
struct PackedDiffuse {
  uint64_t id;
  int16_t velocity[3];
  uint16_t life;
  uint8_t offset[3];
  uint8_t type;
  uint32_t key;
};
static_assert(sizeof(PackedDiffuse) == 24);

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

// Particles [begin, end) of the frame into records[begin, end), and their 64-bit cell keys into
// wide_keys[begin, end) unless wide_keys is null.
void pack_diffuse(const DiffuseFrame& frame, const PackingSteps& steps, size_t begin, size_t end, PackedDiffuse* records,
                  uint64_t* wide_keys);

}  // namespace spume

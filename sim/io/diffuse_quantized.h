#pragma once
// The quantized form of a diffuse frame, as the compact diffuse cache stores it (spume_cache.h).
//
// Positions: integers q = round((p - origin) / step) per axis, origin the frame's lower bounds and step
// given (the pipeline uses the fluid particle radius / kPositionStepsPerRadius). Particles are sorted
// by their cell of 2^7 steps a side (stable: within a cell they keep their order), each cell stored once
// (the key difference to the previous occupied cell and the count), each particle as its three 7-bit
// offsets within the cell (a byte each; the codec's bit shuffle drops the unused bit). Error per axis <= step / 2, plus the rounding of the result to float.
// Velocities: per component round(v / vstep) in 16 bits, vstep = the frame's largest |component| / 32767.
// Error per component <= vstep / 2. Lifetimes: round((life - lmin) / lstep) in 16 bits, lmin the frame's
// shortest lifetime, lstep = (longest - shortest) / 65535. Error <= lstep / 2. Types in 2 bits, ids as
// they are (64 bits; the codec's byte shuffle finds their zero bytes).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "sim/core/frames.h"
#include "sim/io/huge_buffer.h"

namespace spume {

constexpr int kCellOffsetBits = 7;
constexpr double kPositionStepsPerRadius = 64.0;  // position error <= r / 128

struct DiffuseQuantization {
  std::array<double, 3> origin{};  // m
  double position_step = 0.0;      // m
  double velocity_step = 0.0;      // m/s
  double life_origin = 0.0;        // s
  double life_step = 0.0;          // s
  std::array<uint32_t, 3> cells{};  // cells per axis
};

struct QuantizedDiffuse {
  DiffuseQuantization q;
  std::vector<uint64_t> cell_key_steps;  // occupied cells: key minus the previous key (the first: the key)
  std::vector<uint32_t> cell_counts;     // particles in each occupied cell
  HugeBuffer<uint8_t> offsets;           // 3 planes of n: x, y, z offsets within the cell
  HugeBuffer<int16_t> velocities;        // 3 planes of n
  HugeBuffer<uint16_t> lifetimes;
  HugeBuffer<uint8_t> types;             // 2 bits each, 4 a byte, the first in the low bits
  HugeBuffer<uint64_t> ids;
  size_t size() const { return ids.size(); }
};

// The frame in sorted, quantized form; std::nullopt when the frame spans more than 2^31 steps along an
// axis, 2^62 cells or 2^32 particles (the cache then stores it exactly). The frame must be valid
// (finite values, types 0..2); position_step > 0.
std::optional<QuantizedDiffuse> quantize_diffuse(const DiffuseFrame& frame, double position_step);
// Back to particles (in the sorted order). Fails naming `where` when the data contradicts itself.
DiffuseFrame dequantize_diffuse(const QuantizedDiffuse& q, const std::string& where);
// Positions and types only, from the cells, offsets and types of a frame of n particles (the other
// columns may be empty), in the sorted order.
DiffusePoints dequantize_points(const QuantizedDiffuse& q, size_t n, const std::string& where);

}  // namespace spume

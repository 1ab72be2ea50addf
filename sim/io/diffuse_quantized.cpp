#include "sim/io/diffuse_quantized.h"

#include <algorithm>
#include <cmath>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume {
namespace {

constexpr double kMaxSteps = 2147483647.0;  // 2^31 - 1 steps along an axis
constexpr uint64_t kMaxCells = uint64_t(1) << 62;
constexpr size_t kGrain = 1 << 14;

// Stable order of `keys` (LSD radix sort, 16 bits a pass, only as many passes as the largest key needs).
HugeBuffer<uint32_t> stable_order(const HugeBuffer<uint64_t>& keys, uint64_t max_key) {
  const size_t n = keys.size();
  HugeBuffer<uint32_t> order(n), next(n);
  for (size_t i = 0; i < n; ++i) order[i] = uint32_t(i);
  for (int shift = 0; shift < 64 && (max_key >> shift) != 0; shift += 16) {
    std::vector<size_t> start(65537, 0);
    for (size_t i = 0; i < n; ++i) ++start[((keys[i] >> shift) & 0xffff) + 1];
    for (size_t d = 1; d <= 65536; ++d) start[d] += start[d - 1];
    for (size_t i = 0; i < n; ++i) next[start[(keys[order[i]] >> shift) & 0xffff]++] = order[i];
    std::swap(order, next);
  }
  return order;
}

}  // namespace

std::optional<QuantizedDiffuse> quantize_diffuse(const DiffuseFrame& frame, double position_step) {
  const size_t n = frame.size();
  if (n > UINT32_MAX) return std::nullopt;
  QuantizedDiffuse out;
  DiffuseQuantization& q = out.q;
  q.position_step = position_step;
  std::array<double, 3> hi{};
  double vmax = 0.0, lmin = 0.0, lmax = 0.0;
  if (n > 0) {
    for (int a = 0; a < 3; ++a) q.origin[a] = hi[a] = frame.positions[0][a];
    lmin = lmax = frame.lifetimes[0];
  }
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      q.origin[a] = std::min(q.origin[a], double(frame.positions[i][a]));
      hi[a] = std::max(hi[a], double(frame.positions[i][a]));
      vmax = std::max(vmax, std::abs(double(frame.velocities[i][a])));
    }
    lmin = std::min(lmin, double(frame.lifetimes[i]));
    lmax = std::max(lmax, double(frame.lifetimes[i]));
  }
  std::array<uint64_t, 3> qmax{};
  uint64_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    const double span = (hi[a] - q.origin[a]) / position_step;
    if (!(span <= kMaxSteps)) return std::nullopt;
    qmax[a] = uint64_t(std::llround(span));
    q.cells[a] = uint32_t((qmax[a] >> kCellOffsetBits) + 1);
    if (cells > kMaxCells / q.cells[a]) return std::nullopt;
    cells *= q.cells[a];
  }
  q.velocity_step = vmax / 32767.0;
  q.life_origin = lmin;
  q.life_step = (lmax - lmin) / 65535.0;

  // A particle's steps from the origin along axis a (computed again where needed: cheaper than storing).
  auto steps = [&](size_t i, int a) {
    const double s = double(std::llround((double(frame.positions[i][a]) - q.origin[a]) / position_step));
    return uint32_t(std::clamp<double>(s, 0.0, double(qmax[a])));
  };
  HugeBuffer<uint64_t> keys(n);
  parallel_for(n, kGrain, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      keys[i] = (steps(i, 0) >> kCellOffsetBits) +
                q.cells[0] * ((steps(i, 1) >> kCellOffsetBits) + uint64_t(q.cells[1]) * (steps(i, 2) >> kCellOffsetBits));
  });
  const HugeBuffer<uint32_t> order = stable_order(keys, cells - 1);

  uint64_t previous = 0;
  for (size_t k = 0; k < n; ++k) {
    const uint64_t key = keys[order[k]];
    if (k == 0 || key != previous) {
      out.cell_key_steps.push_back(key - previous);
      out.cell_counts.push_back(0);
      previous = key;
    }
    ++out.cell_counts.back();
  }
  out.offsets.resize(3 * n);
  out.velocities.resize(3 * n);
  out.lifetimes.resize(n);
  out.ids.resize(n);
  out.types.resize((n + 3) / 4);
  constexpr uint32_t kOffsetMask = (1u << kCellOffsetBits) - 1;
  parallel_for(n, kGrain, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const size_t i = order[k];
      for (int a = 0; a < 3; ++a) {
        out.offsets[a * n + k] = uint8_t(steps(i, a) & kOffsetMask);
        const double v = q.velocity_step > 0.0 ? double(frame.velocities[i][a]) / q.velocity_step : 0.0;
        out.velocities[a * n + k] = int16_t(std::clamp<long long>(std::llround(v), -32767, 32767));
      }
      const double l = q.life_step > 0.0 ? (double(frame.lifetimes[i]) - lmin) / q.life_step : 0.0;
      out.lifetimes[k] = uint16_t(std::clamp<long long>(std::llround(l), 0, 65535));
      out.ids[k] = frame.ids[i];
    }
  });
  parallel_for(out.types.size(), kGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      uint8_t packed = 0;
      for (size_t k = 4 * b; k < std::min(n, 4 * b + 4); ++k) packed |= uint8_t(uint8_t(frame.types[order[k]]) << (2 * (k % 4)));
      out.types[b] = packed;
    }
  });
  return out;
}

DiffuseFrame dequantize_diffuse(const QuantizedDiffuse& in, const std::string& where) {
  const DiffuseQuantization& q = in.q;
  const size_t n = in.size();
  if (in.cell_key_steps.size() != in.cell_counts.size() || in.offsets.size() != 3 * n ||
      in.velocities.size() != 3 * n || in.lifetimes.size() != n || in.types.size() != (n + 3) / 4)
    fail(where, ": corrupt: quantized columns disagree in length");
  uint64_t cells = 1;
  for (uint32_t c : q.cells) {
    if (c == 0 || cells > kMaxCells / c) fail(where, ": corrupt: cell grid ", q.cells[0], " x ", q.cells[1], " x ", q.cells[2]);
    cells *= c;
  }
  // Where each occupied cell's particles start, checked before any particle is decoded.
  const size_t occupied = in.cell_counts.size();
  std::vector<uint64_t> key(occupied), first(occupied + 1, 0);
  for (size_t c = 0; c < occupied; ++c) {
    const uint64_t previous = c > 0 ? key[c - 1] : 0;
    if (c > 0 && in.cell_key_steps[c] == 0) fail(where, ": corrupt: occupied cell ", c, " repeats the previous one");
    if (in.cell_key_steps[c] >= cells - previous) fail(where, ": corrupt: occupied cell ", c, " lies outside the cell grid");
    key[c] = previous + in.cell_key_steps[c];
    if (in.cell_counts[c] == 0 || in.cell_counts[c] > n - first[c])
      fail(where, ": corrupt: occupied cell ", c, " holds ", in.cell_counts[c], " particles; ", n - first[c], " remain");
    first[c + 1] = first[c] + in.cell_counts[c];
  }
  if (first[occupied] != n) fail(where, ": corrupt: the occupied cells hold ", first[occupied], " particles; the header says ", n);

  DiffuseFrame frame;
  frame.resize(n);
  parallel_for(occupied, 1, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c) {
      const uint64_t cell[3] = {key[c] % q.cells[0], (key[c] / q.cells[0]) % q.cells[1],
                                key[c] / (uint64_t(q.cells[0]) * q.cells[1])};
      for (size_t k = first[c]; k < first[c + 1]; ++k) {
        for (int a = 0; a < 3; ++a) {
          const uint64_t s = (cell[a] << kCellOffsetBits) + in.offsets[a * n + k];
          frame.positions[k][a] = float(q.origin[a] + double(s) * q.position_step);
          frame.velocities[k][a] = float(double(in.velocities[a * n + k]) * q.velocity_step);
        }
        frame.lifetimes[k] = float(q.life_origin + double(in.lifetimes[k]) * q.life_step);
        frame.ids[k] = in.ids[k];
        frame.types[k] = DiffuseType((in.types[k / 4] >> (2 * (k % 4))) & 3u);
      }
    }
  });
  return frame;
}

}  // namespace spume

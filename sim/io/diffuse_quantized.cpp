#include "sim/io/diffuse_quantized.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "sim/core/error.h"
#include "sim/core/huge_pages.h"
#include "sim/core/parallel.h"
#include "sim/io/diffuse_packing.h"

namespace spume {
namespace {

constexpr double kMaxSteps = 2147483647.0;  // 2^31 - 1 steps along an axis
constexpr uint64_t kMaxCells = uint64_t(1) << 62;
constexpr size_t kGrain = 1 << 14;

// Stable order of 64-bit `keys` (serial LSD radix sort, 16 bits a pass, as many passes as max_key
// needs): for frames of more than 2^32 cells, which a simulation's frames never have.
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

// Stable parallel LSD radix sort of (key << 32 | index) pairs by their key (its low `bits` bits), over
// fixed chunks, each counted and scattered by one task: a stable sort has one answer, so neither the
// chunking nor the thread count can change it. Pairs rather than whole quantized particles: 8 bytes a
// particle and 8 of scratch instead of 24 and 24.
void radix_sort(HugeBuffer<uint64_t>& pairs, int bits) {
  const size_t n = pairs.size();
  if (bits == 0 || n < 2) return;  // one cell: the frame's order
  const int passes = (bits + 10) / 11, digit_bits = (bits + passes - 1) / passes;
  const uint32_t buckets = 1u << digit_bits, mask = buckets - 1;
  const size_t chunks = std::clamp<size_t>(n / (1 << 16), 1, 256), chunk = (n + chunks - 1) / chunks;
  std::vector<uint32_t> next(chunks * buckets);
  HugeBuffer<uint64_t> scratch(n);
  for (int pass = 0; pass < passes; ++pass) {
    const int shift = 32 + pass * digit_bits;
    parallel_for(chunks, 1, [&](size_t cb, size_t ce) {
      for (size_t c = cb; c < ce; ++c) {
        uint32_t* count = &next[c * buckets];
        std::fill(count, count + buckets, 0u);
        for (size_t i = c * chunk, end = std::min(n, i + chunk); i < end; ++i) ++count[(pairs[i] >> shift) & mask];
      }
    });
    uint32_t sum = 0;  // chunk c's share of a bucket follows the shares of chunks before it
    for (uint32_t b = 0; b < buckets; ++b)
      for (size_t c = 0; c < chunks; ++c) {
        const uint32_t here = next[c * buckets + b];
        next[c * buckets + b] = sum;
        sum += here;
      }
    parallel_for(chunks, 1, [&](size_t cb, size_t ce) {
      for (size_t c = cb; c < ce; ++c) {
        uint32_t* slot = &next[c * buckets];
        for (size_t i = c * chunk, end = std::min(n, i + chunk); i < end; ++i)
          scratch[slot[(pairs[i] >> shift) & mask]++] = pairs[i];
      }
    });
    std::swap(pairs, scratch);
  }
}

// The occupied cells as they are stored (each key minus the previous one, and the count) from the
// keys in sorted order (sorted_key(k) for slot k).
template <typename SortedKey>
void occupied_cells(size_t n, SortedKey&& sorted_key, QuantizedDiffuse& out) {
  HugeBuffer<uint32_t> first(n + 1);
  const size_t occupied = parallel_select(
      n, [&](size_t k) { return k == 0 || sorted_key(k) != sorted_key(k - 1); },
      [&](size_t k, size_t c) { first[c] = uint32_t(k); });
  first[occupied] = uint32_t(n);
  resize_in_huge_pages(out.cell_key_steps, occupied);
  resize_in_huge_pages(out.cell_counts, occupied);
  parallel_for(occupied, kGrain, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c) {
      out.cell_key_steps[c] = sorted_key(first[c]) - (c > 0 ? sorted_key(first[c - 1]) : 0);
      out.cell_counts[c] = first[c + 1] - first[c];
    }
  });
}

// The quantized columns in the sorted order, particle index_of(k) in slot k, a block of slots a call.
template <typename IndexOf>
void pack_columns(const DiffuseFrame& frame, const PackingSteps& steps, IndexOf&& index_of, QuantizedDiffuse& out) {
  const size_t n = frame.size(), blocks = (n + kPackBlock - 1) / kPackBlock;
  // Sized after the sort, so that its scratch, back in the pool, serves the ids.
  out.offsets.resize(3 * n);
  out.velocities.resize(3 * n);
  out.lifetimes.resize(n);
  out.ids.resize(n);
  out.types.resize((n + 3) / 4);
  parallel_for(blocks, kGrain / kPackBlock, [&](size_t begin, size_t end) {
    uint32_t index[kPackBlock];
    for (size_t b = begin; b < end; ++b) {
      const size_t first = b * kPackBlock, m = std::min(kPackBlock, n - first);
      for (size_t j = 0; j < m; ++j) index[j] = index_of(first + j);
      pack_sorted_block(frame, steps, index, m, first, out);
    }
  });
}

// Rounds half away from zero without a library call (x within +-2^62).
inline int64_t round_to_int(double x) { return int64_t(x + (x >= 0.0 ? 0.5 : -0.5)); }

struct Bounds {
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  double vmax = 0.0, lmin = INFINITY, lmax = -INFINITY;
  void merge(const Bounds& b) {
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], b.lo[a]), hi[a] = std::max(hi[a], b.hi[a]);
    vmax = std::max(vmax, b.vmax), lmin = std::min(lmin, b.lmin), lmax = std::max(lmax, b.lmax);
  }
};

// Minima and maxima are exact whatever the split, so the chunks may be any. They are taken in float,
// the values' own type (converting to double keeps their order), over the flat x, y, z floats 24 at a
// time, so that the loops vectorize: float k of a run of 24 is axis k % 3 (24 = 8 lanes x 3 axes).
Bounds frame_bounds(const DiffuseFrame& frame) {
  constexpr size_t kRun = 24;
  const size_t n = frame.size(), chunks = std::max<size_t>(1, n / kGrain);
  std::vector<Bounds> part(chunks);
  parallel_for(chunks, 1, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c) {
      const size_t begin = c * n / chunks, end = (c + 1) * n / chunks;
      float lo[kRun], hi[kRun], vmax[kRun];
      std::fill_n(lo, kRun, INFINITY), std::fill_n(hi, kRun, -INFINITY), std::fill_n(vmax, kRun, 0.0f);
      float lmin = INFINITY, lmax = -INFINITY;
      if (begin < end) {
        const float* x = frame.positions[begin].data();  // 3 (end - begin) floats
        const float* v = frame.velocities[begin].data();
        const size_t floats = 3 * (end - begin), runs = floats / kRun;
        for (size_t r = 0; r < runs; ++r)
          for (size_t k = 0; k < kRun; ++k) {
            const float xk = x[r * kRun + k], vk = std::abs(v[r * kRun + k]);
            lo[k] = std::min(lo[k], xk), hi[k] = std::max(hi[k], xk), vmax[k] = std::max(vmax[k], vk);
          }
        for (size_t f = runs * kRun; f < floats; ++f) {  // the rest, by the same rule: float f is axis f % 3
          const size_t k = f % 3;
          lo[k] = std::min(lo[k], x[f]), hi[k] = std::max(hi[k], x[f]), vmax[k] = std::max(vmax[k], std::abs(v[f]));
        }
        float lmins[8], lmaxs[8];
        std::fill_n(lmins, 8, INFINITY), std::fill_n(lmaxs, 8, -INFINITY);
        const float* life = &frame.lifetimes[begin];
        const size_t count = end - begin;
        for (size_t r = 0; r + 8 <= count; r += 8)
          for (size_t k = 0; k < 8; ++k) lmins[k] = std::min(lmins[k], life[r + k]), lmaxs[k] = std::max(lmaxs[k], life[r + k]);
        for (size_t i = count / 8 * 8; i < count; ++i) lmins[0] = std::min(lmins[0], life[i]), lmaxs[0] = std::max(lmaxs[0], life[i]);
        for (size_t k = 0; k < 8; ++k) lmin = std::min(lmin, lmins[k]), lmax = std::max(lmax, lmaxs[k]);
      }
      Bounds& b = part[c];
      for (size_t k = 0; k < kRun; ++k) {
        b.lo[k % 3] = std::min(b.lo[k % 3], double(lo[k])), b.hi[k % 3] = std::max(b.hi[k % 3], double(hi[k]));
        b.vmax = std::max(b.vmax, double(vmax[k]));
      }
      b.lmin = double(lmin), b.lmax = double(lmax);
    }
  });
  Bounds all;
  for (const Bounds& b : part) all.merge(b);
  if (n == 0) all = Bounds{{0, 0, 0}, {0, 0, 0}, 0.0, 0.0, 0.0};
  return all;
}

}  // namespace

std::optional<QuantizedDiffuse> quantize_diffuse(const DiffuseFrame& frame, double position_step) {
  const size_t n = frame.size();
  if (n > UINT32_MAX) return std::nullopt;
  QuantizedDiffuse out;
  DiffuseQuantization& q = out.q;
  q.position_step = position_step;
  const Bounds bounds = frame_bounds(frame);
  std::array<uint64_t, 3> qmax{};
  uint64_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    q.origin[a] = bounds.lo[a];
    const double span = (bounds.hi[a] - bounds.lo[a]) / position_step;
    if (!(span <= kMaxSteps)) return std::nullopt;
    qmax[a] = uint64_t(round_to_int(span));
    q.cells[a] = uint32_t((qmax[a] >> kCellOffsetBits) + 1);
    if (cells > kMaxCells / q.cells[a]) return std::nullopt;
    cells *= q.cells[a];
  }
  q.velocity_step = bounds.vmax / 32767.0;
  q.life_origin = bounds.lmin;
  q.life_step = (bounds.lmax - bounds.lmin) / 65535.0;

  // Reciprocals: a product's rounding (half an ulp of a double) is far below the float rounding the
  // stated bounds allow for.
  PackingSteps steps;
  for (int a = 0; a < 3; ++a) steps.origin[a] = q.origin[a], steps.max_steps[a] = double(qmax[a]);
  steps.per_step = 1.0 / position_step;
  steps.per_velocity_step = q.velocity_step > 0.0 ? 1.0 / q.velocity_step : 0.0;
  steps.life_origin = q.life_origin;
  steps.per_life_step = q.life_step > 0.0 ? 1.0 / q.life_step : 0.0;
  steps.cells = q.cells;
  // Each particle's cell key, in the frame's order, then into cell order (stable: within a cell the
  // frame's order), then the columns gathered in that order.
  const bool narrow = cells - 1 <= UINT32_MAX;
  HugeBuffer<uint64_t> keys(n);
  parallel_for(n, kGrain, [&](size_t begin, size_t end) { cell_keys(frame, steps, begin, end, keys.data(), narrow); });
  if (narrow) {
    radix_sort(keys, int(std::bit_width(cells - 1)));
    occupied_cells(n, [&](size_t k) { return keys[k] >> 32; }, out);
    pack_columns(frame, steps, [&](size_t k) { return uint32_t(keys[k]); }, out);
  } else {
    const HugeBuffer<uint32_t> order = stable_order(keys, cells - 1);
    occupied_cells(n, [&](size_t k) { return keys[order[k]]; }, out);
    pack_columns(frame, steps, [&](size_t k) { return order[k]; }, out);
  }
  return out;
}

namespace {

// The occupied cells' keys and where each one's particles start, checked before any particle is
// decoded: keys increase inside the grid, every cell holds at least one particle, all n in all.
struct CellTable {
  std::vector<uint64_t> key, first;  // first: occupied + 1 entries
};

CellTable checked_cells(const QuantizedDiffuse& in, size_t n, const std::string& where) {
  const DiffuseQuantization& q = in.q;
  if (in.cell_key_steps.size() != in.cell_counts.size()) fail(where, ": corrupt: quantized columns disagree in length");
  uint64_t cells = 1;
  for (uint32_t c : q.cells) {
    if (c == 0 || cells > kMaxCells / c) fail(where, ": corrupt: cell grid ", q.cells[0], " x ", q.cells[1], " x ", q.cells[2]);
    cells *= c;
  }
  const size_t occupied = in.cell_counts.size();
  CellTable t{std::vector<uint64_t>(occupied), std::vector<uint64_t>(occupied + 1, 0)};
  for (size_t c = 0; c < occupied; ++c) {
    const uint64_t previous = c > 0 ? t.key[c - 1] : 0;
    if (c > 0 && in.cell_key_steps[c] == 0) fail(where, ": corrupt: occupied cell ", c, " repeats the previous one");
    if (in.cell_key_steps[c] >= cells - previous) fail(where, ": corrupt: occupied cell ", c, " lies outside the cell grid");
    t.key[c] = previous + in.cell_key_steps[c];
    if (in.cell_counts[c] == 0 || in.cell_counts[c] > n - t.first[c])
      fail(where, ": corrupt: occupied cell ", c, " holds ", in.cell_counts[c], " particles; ", n - t.first[c], " remain");
    t.first[c + 1] = t.first[c] + in.cell_counts[c];
  }
  if (t.first[occupied] != n) fail(where, ": corrupt: the occupied cells hold ", t.first[occupied], " particles; the header says ", n);
  return t;
}

// Calls decode(particle, cell) for every particle, each occupied cell by one task.
template <typename Decode>
void for_each_particle(const QuantizedDiffuse& in, const CellTable& t, Decode&& decode) {
  const DiffuseQuantization& q = in.q;
  parallel_for(t.key.size(), 1, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c) {
      const uint64_t key = t.key[c];
      const uint64_t cell[3] = {key % q.cells[0], (key / q.cells[0]) % q.cells[1], key / (uint64_t(q.cells[0]) * q.cells[1])};
      for (size_t k = t.first[c]; k < t.first[c + 1]; ++k) decode(k, cell);
    }
  });
}

Vec3f position_of(const QuantizedDiffuse& in, size_t n, size_t k, const uint64_t cell[3]) {
  Vec3f p;
  for (int a = 0; a < 3; ++a) {
    const uint64_t s = (cell[a] << kCellOffsetBits) + in.offsets[a * n + k];
    p[a] = float(in.q.origin[a] + double(s) * in.q.position_step);
  }
  return p;
}

DiffuseType type_of(const QuantizedDiffuse& in, size_t k) { return DiffuseType((in.types[k / 4] >> (2 * (k % 4))) & 3u); }

}  // namespace

DiffuseFrame dequantize_diffuse(const QuantizedDiffuse& in, const std::string& where) {
  const DiffuseQuantization& q = in.q;
  const size_t n = in.size();
  if (in.offsets.size() != 3 * n || in.velocities.size() != 3 * n || in.lifetimes.size() != n ||
      in.types.size() != (n + 3) / 4)
    fail(where, ": corrupt: quantized columns disagree in length");
  const CellTable cells = checked_cells(in, n, where);

  DiffuseFrame frame;
  // Fresh output memory costs a page fault per 4 KiB on first touch: ask for 2 MiB pages first.
  frame.reserve(n);
  advise_huge_pages(frame.ids.data(), n * sizeof(uint64_t));
  advise_huge_pages(frame.positions.data(), n * sizeof(Vec3f));
  advise_huge_pages(frame.velocities.data(), n * sizeof(Vec3f));
  advise_huge_pages(frame.lifetimes.data(), n * sizeof(float));
  advise_huge_pages(frame.types.data(), n);
  frame.resize(n);
  for_each_particle(in, cells, [&](size_t k, const uint64_t cell[3]) {
    frame.positions[k] = position_of(in, n, k, cell);
    for (int a = 0; a < 3; ++a) frame.velocities[k][a] = float(double(in.velocities[a * n + k]) * q.velocity_step);
    frame.lifetimes[k] = float(q.life_origin + double(in.lifetimes[k]) * q.life_step);
    frame.ids[k] = in.ids[k];
    frame.types[k] = type_of(in, k);
  });
  return frame;
}

DiffusePoints dequantize_points(const QuantizedDiffuse& in, size_t n, const std::string& where) {
  if (in.offsets.size() != 3 * n || in.types.size() != (n + 3) / 4)
    fail(where, ": corrupt: quantized columns disagree in length");
  const CellTable cells = checked_cells(in, n, where);
  DiffusePoints points;
  resize_in_huge_pages(points.positions, n);
  resize_in_huge_pages(points.types, n);
  for_each_particle(in, cells, [&](size_t k, const uint64_t cell[3]) {
    points.positions[k] = position_of(in, n, k, cell);
    points.types[k] = type_of(in, k);
  });
  return points;
}

}  // namespace spume

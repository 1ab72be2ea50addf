#include "sim/diffuse/narrow_band.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/grid/distance_transform.h"

namespace spume {
namespace {

enum Kind : uint8_t { Empty, Occupied, Blocked, Air, Enclosed, Extrapolated, Queued, Sealed };

// Beyond this many cells the frame is not examined (a dense grid of it would take too much memory).
constexpr size_t kMaxCells = size_t(1) << 24;

struct Lattice {
  std::array<int64_t, 3> dims{};
  size_t index(int64_t x, int64_t y, int64_t z) const { return size_t((z * dims[1] + y) * dims[0] + x); }
  std::array<int64_t, 3> coords(size_t i) const {
    const int64_t x = int64_t(i) % dims[0], y = (int64_t(i) / dims[0]) % dims[1], z = int64_t(i) / (dims[0] * dims[1]);
    return {x, y, z};
  }
  bool in(int64_t x, int64_t y, int64_t z) const {
    return x >= 0 && y >= 0 && z >= 0 && x < dims[0] && y < dims[1] && z < dims[2];
  }
  bool padding(const std::array<int64_t, 3>& c) const {
    for (int a = 0; a < 3; ++a)
      if (c[a] == 0 || c[a] == dims[a] - 1) return true;
    return false;
  }
};

constexpr std::array<std::array<int, 3>, 6> kFaces = {{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};

float quantile(std::vector<float>& values, double q) {
  const size_t k = std::min(values.size() - 1, size_t(q * double(values.size())));
  std::nth_element(values.begin(), values.begin() + ptrdiff_t(k), values.end());
  return values[k];
}

}  // namespace

std::string describe_interior(const InteriorFill& f) {
  const std::string cells = str(" cells of h = ", f.cell, " m");
  if (f.skipped) return str("not tested (the particles spread over more than 16M cells of h = ", f.cell, " m)");
  if (!f.large)
    return str("full (", f.enclosed_cells, " enclosed empty", cells, " beside ", f.occupied_cells,
               " occupied: below the ", 100.0 * kNarrowBandShare, "% of a narrow band)");
  const std::string enclosed = str(f.enclosed_cells, " enclosed empty", cells, " beside ", f.occupied_cells, " occupied");
  const std::string depth = str(f.depth_low, " to ", f.depth_high, " m under the surface (10th to 90th percentile of its edge)");
  if (f.narrow_band)
    return str("a NARROW BAND: ", enclosed, ", in a FLIP cache (fluid.particles = flip), which keeps particles only near "
               "the surface; its edge lies ", depth);
  return str("ENCLOSED, not filled: ", enclosed, ", whose edge lies ", depth, "; the cache is not known to be FLIP, so "
             "this is taken as air (a pocket of it), not as the empty interior of a narrow band (set fluid.particles "
             "to \"flip\" to fill it)");
}

bool InteriorFiller::flood(const std::vector<Vec3f>& positions, float cell, const Vec3f& gravity,
                           const SolidSet* solids) {
  const size_t n = positions.size();
  Vec3f lo = positions[0], hi = lo;
  for (const Vec3f& p : positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  origin_ = lo - Vec3f::Constant(cell);  // one empty layer of padding on every side
  Lattice g;
  double total = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double span = std::floor(double(hi[a] - lo[a]) / double(cell)) + 3.0;
    if (!(span < double(kMaxCells))) return false;
    g.dims[a] = int64_t(span);
    total *= span;
  }
  if (total > double(kMaxCells)) return false;
  dims_ = g.dims;
  const size_t cells = size_t(total);

  // Particles by cell (counting sort, in index order within a cell).
  cell_of_.resize(n);
  parallel_for(n, 1 << 14, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      std::array<int64_t, 3> c;
      for (int a = 0; a < 3; ++a)
        c[a] = std::clamp(int64_t(std::floor((positions[i][a] - origin_[a]) / cell)), int64_t(1), g.dims[a] - 2);
      cell_of_[i] = uint32_t(g.index(c[0], c[1], c[2]));
    }
  });
  start_.assign(cells + 1, 0);
  for (size_t i = 0; i < n; ++i) ++start_[cell_of_[i] + 1];
  for (size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  members_.resize(n);
  {
    std::vector<uint32_t> fill_at(start_.begin(), start_.end() - 1);
    for (size_t i = 0; i < n; ++i) members_[fill_at[cell_of_[i]]++] = uint32_t(i);
  }

  // Kinds: occupied, inside a solid, the padding (walls, except the layer above, where the air is).
  kind_.assign(cells, Empty);
  int up_axis = -1, up_sign = 0;
  if (gravity.squaredNorm() > 0.0f) {
    gravity.cwiseAbs().maxCoeff(&up_axis);
    up_sign = gravity[up_axis] < 0.0f ? 1 : -1;
  }
  const bool see_solids = solids && !solids->empty();
  parallel_for(cells, 4096, [&](size_t b, size_t e) {
    for (size_t c = b; c < e; ++c) {
      if (start_[c + 1] > start_[c]) {
        kind_[c] = Occupied;
        continue;
      }
      const auto xyz = g.coords(c);
      const bool padding = g.padding(xyz);
      bool top = false;
      if (up_axis >= 0) top = up_sign > 0 ? xyz[up_axis] == g.dims[up_axis] - 1 : xyz[up_axis] == 0;
      if (padding && up_axis < 0) kind_[c] = Air;
      else if (top) kind_[c] = Air;
      else if (padding) kind_[c] = Blocked;
      else if (see_solids) {
        const Vec3f index_centre = Vec3f(float(xyz[0]), float(xyz[1]), float(xyz[2])) + Vec3f::Constant(0.5f);
        const Vec3f centre = origin_ + index_centre * cell;
        if (solids->inside(centre)) kind_[c] = Blocked;
      }
    }
  });

  // Empty cells with a particle within half a cell (2r when h = 4r: one particle spacing) of them are
  // sealed: the flood does not pass them. FLIP seeds its particles at random, and cells not aligned
  // with its grid leave a few empty at random, which alone would open a band to the air (the shared
  // jet's frame 30 was a band on cells of 0.03125 m and none on cells of 0.0312 m).
  const float reach2 = 0.25f * cell * cell;
  parallel_for(cells, 4096, [&](size_t b, size_t e) {
    for (size_t c = b; c < e; ++c) {
      if (kind_[c] != Empty) continue;
      const auto xyz = g.coords(c);
      const Vec3f box_lo = origin_ + Vec3f(float(xyz[0]), float(xyz[1]), float(xyz[2])) * cell;
      bool near = false;
      for (int dz = -1; dz <= 1 && !near; ++dz)
        for (int dy = -1; dy <= 1 && !near; ++dy)
          for (int dx = -1; dx <= 1 && !near; ++dx) {
            const size_t nb = g.index(xyz[0] + dx, xyz[1] + dy, xyz[2] + dz);  // Empty cells are not padding
            for (uint32_t k = start_[nb]; k < start_[nb + 1] && !near; ++k) {
              const Vec3f& p = positions[members_[k]];
              const Vec3f out = (box_lo - p).cwiseMax(p - box_lo - Vec3f::Constant(cell)).cwiseMax(0.0f);
              near = out.squaredNorm() <= reach2;
            }
          }
      if (near) kind_[c] = Sealed;
    }
  });

  // Flood fill from the air through empty cells (6-connected).
  queue_.clear();
  for (size_t c = 0; c < cells; ++c)
    if (kind_[c] == Air) queue_.push_back(uint32_t(c));
  for (size_t q = 0; q < queue_.size(); ++q) {
    const auto xyz = g.coords(queue_[q]);
    for (const auto& f : kFaces) {
      const int64_t x = xyz[0] + f[0], y = xyz[1] + f[1], z = xyz[2] + f[2];
      if (!g.in(x, y, z)) continue;
      const size_t nb = g.index(x, y, z);
      if (kind_[nb] == Empty) kind_[nb] = Air, queue_.push_back(uint32_t(nb));
    }
  }
  // Sealed cells the air touches lie outside the water (above its surface, in a gap's mouth); the
  // others are inside, as the empty cells the air never reached are.
  std::vector<uint32_t> outside;
  for (size_t c = 0; c < cells; ++c) {
    if (kind_[c] != Sealed) continue;
    const auto xyz = g.coords(c);
    for (const auto& f : kFaces)
      if (kind_[g.index(xyz[0] + f[0], xyz[1] + f[1], xyz[2] + f[2])] == Air) {
        outside.push_back(uint32_t(c));
        break;
      }
  }
  for (const uint32_t c : outside) kind_[c] = Air;
  for (size_t c = 0; c < cells; ++c)
    if (kind_[c] == Empty || kind_[c] == Sealed) kind_[c] = Enclosed;
  return true;
}

InteriorFill InteriorFiller::examine(const std::vector<Vec3f>& positions, float cell, const Vec3f& gravity,
                                     bool flip_source) {
  InteriorFill result;
  result.cell = cell, result.flip_source = flip_source;
  if (positions.empty() || !(cell > 0.0f)) return result;
  if (!flood(positions, cell, gravity, nullptr)) {
    result.skipped = true;
    return result;
  }
  for (const uint8_t k : kind_) result.occupied_cells += k == Occupied, result.enclosed_cells += k == Enclosed;
  result.large = result.enclosed_cells >= kNarrowBandMinCells &&
                 double(result.enclosed_cells) >= kNarrowBandShare * double(result.occupied_cells);
  if (!result.large) return result;

  // The depth of the enclosed interior's edge: from each occupied cell beside it to the nearest cell
  // the air reaches or of the padding (the particles' bounds may be a surface too: a band along a side).
  Lattice g;
  g.dims = dims_;
  std::vector<uint8_t> outside(kind_.size());
  for (size_t c = 0; c < kind_.size(); ++c) outside[c] = kind_[c] == Air || g.padding(g.coords(c));
  const std::vector<float> d2 = squared_distance_to_seeds(outside, dims_);
  std::vector<float> depths;
  for (size_t c = 0; c < kind_.size(); ++c) {
    if (kind_[c] != Occupied) continue;
    const auto xyz = g.coords(c);
    for (const auto& f : kFaces)
      if (kind_[g.index(xyz[0] + f[0], xyz[1] + f[1], xyz[2] + f[2])] == Enclosed) {
        depths.push_back(std::sqrt(d2[c]) * cell);
        break;
      }
  }
  if (depths.empty()) return result;  // not reached: an enclosed cell borders an occupied one
  result.depth_low = quantile(depths, 0.1);
  result.depth_median = quantile(depths, 0.5);
  result.depth_high = quantile(depths, 0.9);
  result.narrow_band = flip_source;
  return result;
}

size_t InteriorFiller::fill(FluidStepState& state, float cell, float spacing, const Vec3f& gravity,
                            const SolidSet* solids) {
  if (state.positions.empty() || !(cell > 0.0f) || !(spacing > 0.0f)) return 0;
  spacing = std::min(spacing, cell);
  if (!flood(state.positions, cell, gravity, solids)) return 0;
  Lattice g;
  g.dims = dims_;
  const size_t cells = kind_.size();

  // Velocities: each occupied cell's mean, carried into the enclosed cells layer by layer (each
  // layer the mean of its 6-neighbours already set), so every filled cell gets the nearest water's.
  cell_velocity_.assign(cells, Vec3f::Zero());
  cell_motion_.assign(cells, Vec3f::Zero());
  parallel_for(cells, 4096, [&](size_t b, size_t e) {
    for (size_t c = b; c < e; ++c) {
      if (kind_[c] != Occupied) continue;
      Vec3f v = Vec3f::Zero(), m = Vec3f::Zero();
      for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) v += state.velocities[members_[k]], m += state.motion[members_[k]];
      const float inv = 1.0f / float(start_[c + 1] - start_[c]);
      cell_velocity_[c] = v * inv, cell_motion_[c] = m * inv;
    }
  });
  auto known = [&](size_t c) { return kind_[c] == Occupied || kind_[c] == Extrapolated; };
  queue_.clear();
  for (size_t c = 0; c < cells; ++c) {
    if (kind_[c] != Enclosed) continue;
    const auto xyz = g.coords(c);
    for (const auto& f : kFaces)
      if (kind_[g.index(xyz[0] + f[0], xyz[1] + f[1], xyz[2] + f[2])] == Occupied) {
        kind_[c] = Queued, queue_.push_back(uint32_t(c));
        break;
      }
  }
  std::vector<uint32_t> next;
  std::vector<Vec3f> layer_v, layer_m;
  while (!queue_.empty()) {
    layer_v.assign(queue_.size(), Vec3f::Zero());
    layer_m.assign(queue_.size(), Vec3f::Zero());
    for (size_t q = 0; q < queue_.size(); ++q) {
      const auto xyz = g.coords(queue_[q]);
      int count = 0;
      for (const auto& f : kFaces) {
        const size_t nb = g.index(xyz[0] + f[0], xyz[1] + f[1], xyz[2] + f[2]);  // padding keeps it inside
        if (known(nb)) layer_v[q] += cell_velocity_[nb], layer_m[q] += cell_motion_[nb], ++count;
      }
      if (count > 0) layer_v[q] /= float(count), layer_m[q] /= float(count);
    }
    next.clear();
    for (size_t q = 0; q < queue_.size(); ++q) {
      const uint32_t c = queue_[q];
      cell_velocity_[c] = layer_v[q], cell_motion_[c] = layer_m[q], kind_[c] = Extrapolated;
    }
    for (const uint32_t c : queue_) {
      const auto xyz = g.coords(c);
      for (const auto& f : kFaces) {
        const size_t nb = g.index(xyz[0] + f[0], xyz[1] + f[1], xyz[2] + f[2]);
        if (kind_[nb] == Enclosed) kind_[nb] = Queued, next.push_back(uint32_t(nb));
      }
    }
    queue_.swap(next);
  }

  // Lattice points of spacing `spacing` in the enclosed cells and the occupied cells bordering them,
  // kept where no particle lies within 0.8 spacings: a lattice offset by half a spacing from the band's
  // lies 0.87 spacings from it, and one layer too many at the band's inner edge (deep water) is safer
  // than the gap of a layer that a full spacing leaves there.
  const double ratio = double(cell) / double(spacing);
  auto first_point = [&](int64_t c) { return int64_t(std::ceil(double(c) * ratio - 0.5)); };
  const float spacing2 = 0.64f * spacing * spacing;
  size_t filled = 0;
  for (size_t c = 0; c < cells; ++c) {
    const auto xyz = g.coords(c);
    bool candidate = kind_[c] == Extrapolated || kind_[c] == Enclosed;
    if (kind_[c] == Occupied)
      for (int dz = -1; dz <= 1 && !candidate; ++dz)
        for (int dy = -1; dy <= 1 && !candidate; ++dy)
          for (int dx = -1; dx <= 1 && !candidate; ++dx) {
            const uint8_t k = kind_[g.index(xyz[0] + dx, xyz[1] + dy, xyz[2] + dz)];
            candidate = k == Extrapolated || k == Enclosed;
          }
    if (!candidate) continue;
    for (int64_t k = first_point(xyz[2]); k < first_point(xyz[2] + 1); ++k)
      for (int64_t j = first_point(xyz[1]); j < first_point(xyz[1] + 1); ++j)
        for (int64_t i = first_point(xyz[0]); i < first_point(xyz[0] + 1); ++i) {
          const Vec3f p = origin_ + Vec3f(float(i) + 0.5f, float(j) + 0.5f, float(k) + 0.5f) * spacing;
          bool near = false;
          for (int dz = -1; dz <= 1 && !near; ++dz)
            for (int dy = -1; dy <= 1 && !near; ++dy)
              for (int dx = -1; dx <= 1 && !near; ++dx) {
                const size_t nb = g.index(xyz[0] + dx, xyz[1] + dy, xyz[2] + dz);
                for (uint32_t m = start_[nb]; m < start_[nb + 1] && !near; ++m)
                  near = (state.positions[members_[m]] - p).squaredNorm() < spacing2;
              }
          if (near) continue;
          state.positions.push_back(p);
          state.velocities.push_back(cell_velocity_[c]);
          state.motion.push_back(cell_motion_[c]);
          state.masses.push_back(0.0f);
          state.ids.push_back(kFillerId);
          ++filled;
        }
  }
  return filled;
}

}  // namespace spume

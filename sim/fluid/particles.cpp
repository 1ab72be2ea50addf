#include "sim/fluid/particles.h"

#include <algorithm>
#include <cmath>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume::fluid {

void Particles::resize(size_t n) {
  x.resize(n);
  v.resize(n);
  id.resize(n);
  density_warm.resize(n);
  divergence_warm.resize(n);
  density.resize(n);
  factor.resize(n);
  accel.resize(n);
  pressure.resize(n);
  source.resize(n);
  x4.resize(n);
  v4.resize(n);
}

namespace {
template <typename T>
void permute(std::vector<T>& a, std::span<const uint32_t> order, std::vector<T>& scratch) {
  scratch.resize(a.size());
  parallel_for(a.size(), 4096, [&](size_t b, size_t e) {
    for (size_t k = b; k < e; ++k) scratch[k] = a[order[k]];
  });
  a.swap(scratch);
}
}  // namespace

void Particles::reorder(std::span<const uint32_t> order) {
  std::vector<Vec3f> vec_scratch;
  permute(x, order, vec_scratch);
  permute(v, order, vec_scratch);
  std::vector<uint32_t> id_scratch;
  permute(id, order, id_scratch);
  std::vector<float> f_scratch;
  permute(density_warm, order, f_scratch);
  permute(divergence_warm, order, f_scratch);
}

BlockLattice block_lattice(const FluidBlock& b, float radius) {
  const double d = 2.0 * double(radius);
  BlockLattice l;
  for (int a = 0; a < 3; ++a) {
    const double extent = double(b.max[a]) - double(b.min[a]);
    // Tolerate extents that are multiples of d up to rounding; clamped so that an absurd block is
    // counted (and refused), not overflowed.
    l.n[a] = std::clamp(std::floor(extent / d + 1e-4), 0.0, 4.0e9);
    l.start[a] = double(b.min[a]) + 0.5 * (extent - l.n[a] * d) + 0.5 * d;
  }
  return l;
}

Particles fill_blocks(const std::vector<FluidBlock>& blocks, float radius, const SolidSet& solids, float clearance,
                      size_t& skipped) {
  const double d = 2.0 * double(radius);
  std::vector<Vec3f> points;
  skipped = 0;
  for (size_t bi = 0; bi < blocks.size(); ++bi) {
    const FluidBlock& b = blocks[bi];
    if (!finite(b.min) || !finite(b.max) || !(b.min.array() < b.max.array()).all())
      fail("fluid block ", bi, ": min must be below max on every axis");
    const BlockLattice l = block_lattice(b, radius);
    if (l.count() > 2.0e9) fail("fluid block ", bi, ": too many particles for radius ", radius);
    const int n[3] = {int(l.n[0]), int(l.n[1]), int(l.n[2])};
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const Vec3f p(float(l.start[0] + i * d), float(l.start[1] + j * d), float(l.start[2] + k * d));
          if (solids.inside(p) || (clearance > 0.0f && solids.obstacle_within(p, clearance))) {
            ++skipped;
            continue;
          }
          points.push_back(p);
        }
  }
  if (points.size() >= size_t(UINT32_MAX)) fail("fluid blocks: ", points.size(), " particles is too many");
  Particles out;
  out.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    out.x[i] = points[i];
    out.v[i] = Vec3f::Zero();
    out.id[i] = uint32_t(i);
  }
  return out;
}

}  // namespace spume::fluid

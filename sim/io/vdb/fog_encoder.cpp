#include "sim/io/vdb/openvdb_io.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/io/vdb/file_bytes.h"

namespace spume::openvdb_io {
namespace {

constexpr double kMostVoxelWrites = 2e10;  // about an hour of splatting on one core

void check_look(const FogLook& look) {
  if (!(look.voxel > 0.0f) || !std::isfinite(look.voxel))
    fail("fog volumes: voxel size ", look.voxel, " m is not a positive number");
  bool any = false;
  for (float r : look.radius) {
    if (!(r >= 0.0f) || !std::isfinite(r)) fail("fog volumes: radius ", r, " m is not a number >= 0");
    any = any || r > 0.0f;
  }
  if (!any) fail("fog volumes: no diffuse type is drawn (every render.*.radius is 0), so there is nothing to fill");
  // A sphere of 64 voxels' radius touches about a million voxels: far finer than anything drawn.
  for (float r : look.radius)
    if (r > 64.0f * look.voxel)
      fail("fog volumes: a radius of ", r, " m is ", r / look.voxel, " voxels of ", look.voxel,
           " m; at most 64 are allowed (choose a larger voxel)");
}

}  // namespace

namespace {

constexpr size_t kChunk = size_t(1) << 20;  // particles a chunk: fixed by the data, never by the threads

// One chunk's sums: the volume fraction per drawn type and their total x velocity.
struct FogGrids {
  std::array<openvdb::FloatGrid::Ptr, kDiffuseTypeCount> fraction;
  openvdb::Vec3SGrid::Ptr momentum;

  FogGrids() = default;
  explicit FogGrids(const FogLook& look) : momentum(openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f))) {
    for (int t = 0; t < kDiffuseTypeCount; ++t)
      if (look.radius[size_t(t)] > 0.0f) fraction[size_t(t)] = openvdb::FloatGrid::create(0.0f);
  }

  void splat(const DiffuseFrame& frame, size_t begin, size_t end, const FogLook& look, double voxel_volume,
             std::vector<VoxelWeight>& weights) {
    std::array<std::optional<openvdb::FloatGrid::Accessor>, kDiffuseTypeCount> type_at;
    for (int t = 0; t < kDiffuseTypeCount; ++t)
      if (fraction[size_t(t)]) type_at[size_t(t)].emplace(fraction[size_t(t)]->getAccessor());
    auto momentum_at = momentum->getAccessor();
    for (size_t i = begin; i < end; ++i) {
      const size_t t = size_t(frame.types[i]);
      if (t >= kDiffuseTypeCount || !type_at[t]) continue;
      const double r = look.radius[t];
      const double share = 4.0 / 3.0 * M_PI * r * r * r / voxel_volume;  // the sphere in voxels
      const openvdb::Vec3s v(frame.velocities[i].x(), frame.velocities[i].y(), frame.velocities[i].z());
      sphere_voxel_weights(frame.positions[i], float(r), look.voxel, weights);
      for (const VoxelWeight& w : weights) {
        const openvdb::Coord ijk(w.ijk[0], w.ijk[1], w.ijk[2]);
        const float add = float(share * w.weight);
        type_at[t]->setValue(ijk, type_at[t]->getValue(ijk) + add);
        momentum_at.setValue(ijk, momentum_at.getValue(ijk) + v * add);
      }
    }
  }

  // this += other, voxel by voxel (other is emptied).
  void add(FogGrids& other) {
    for (size_t t = 0; t < fraction.size(); ++t)
      if (fraction[t]) openvdb::tools::compSum(*fraction[t], *other.fraction[t]);
    openvdb::tools::compSum(*momentum, *other.momentum);
  }
};

}  // namespace

std::string fog_bytes(const DiffuseFrame& frame, const FogLook& look) {
  check_look(look);
  // The splat's work: each sphere touches about 4/3 pi (r/voxel + 1)^3 voxels (8 at least). A voxel far
  // too small for a frame would run for hours: refuse it with the figures.
  const auto count = frame.count_by_type();
  double writes = 0.0;
  for (size_t t = 0; t < kDiffuseTypeCount; ++t)
    if (look.radius[t] > 0.0f)
      writes += double(count[t]) * std::max(8.0, 4.19 * std::pow(look.radius[t] / look.voxel + 1.0, 3.0));
  if (writes > kMostVoxelWrites)
    fail("fog volumes: voxels of ", look.voxel, " m would have this frame's ", frame.size(), " particles write about ",
         writes, " voxel values, over the ", kMostVoxelWrites, " allowed; choose a larger voxel (output.fog)");
  initialize_openvdb();
  const openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(look.voxel);
  const double voxel_volume = double(look.voxel) * look.voxel * look.voxel;
  // Fixed chunks of particles, each splatted in particle order into grids of its own, then added chunk
  // by chunk in order: every voxel's float sum has the same order for any thread count.
  const size_t chunks = std::max<size_t>(1, (frame.size() + kChunk - 1) / kChunk);
  std::vector<FogGrids> part(chunks);
  parallel_for(chunks, 1, [&](size_t cb, size_t ce) {
    std::vector<VoxelWeight> weights;
    for (size_t c = cb; c < ce; ++c) {
      part[c] = FogGrids(look);
      part[c].splat(frame, c * kChunk, std::min(frame.size(), (c + 1) * kChunk), look, voxel_volume, weights);
    }
  });
  FogGrids& all = part[0];
  for (size_t c = 1; c < chunks; ++c) all.add(part[c]);
  std::array<openvdb::FloatGrid::Ptr, kDiffuseTypeCount>& fraction = all.fraction;
  const openvdb::Vec3SGrid::Ptr velocity = all.momentum;  // sum of fraction x velocity, divided below
  // The total, added type by type in type order.
  const openvdb::FloatGrid::Ptr density = openvdb::FloatGrid::create(0.0f);
  for (const openvdb::FloatGrid::Ptr& f : fraction)
    if (f) {
      const openvdb::FloatGrid::Ptr copy = f->deepCopy();
      openvdb::tools::compSum(*density, *copy);
    }
  for (auto it = velocity->beginValueOn(); it; ++it) {
    const float d = density->tree().getValue(it.getCoord());
    it.setValue(d > 0.0f ? *it / d : openvdb::Vec3s(0.0f));
  }
  openvdb::GridCPtrVec grids;
  auto add = [&](const openvdb::GridBase::Ptr& grid, const std::string& name) {
    grid->setTransform(transform);
    grid->setName(name);
    grid->insertMeta("frame", openvdb::Int32Metadata(frame.index));
    grid->insertMeta("time", openvdb::DoubleMetadata(frame.time));
    grid->insertMeta("alpha", openvdb::FloatMetadata(look.alpha));
    grids.push_back(grid);
  };
  for (int t = 0; t < kDiffuseTypeCount; ++t)
    if (fraction[size_t(t)]) {
      fraction[size_t(t)]->setGridClass(openvdb::GRID_FOG_VOLUME);
      fraction[size_t(t)]->insertMeta("radius", openvdb::FloatMetadata(look.radius[size_t(t)]));
      add(fraction[size_t(t)], to_string(DiffuseType(t)));
    }
  density->setGridClass(openvdb::GRID_FOG_VOLUME);
  add(density, "density");
  velocity->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
  add(velocity, "v");
  return vdb_file_bytes(grids);
}

}  // namespace spume::openvdb_io

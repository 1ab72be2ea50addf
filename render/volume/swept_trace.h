#pragma once
// Motion blur's candidate search and trace (MODEL.md §13). Each drawn particle's path over the
// shutter is bounded by a sphere (the path's chord, its sag under gravity and the radius), projected
// to a pixel rectangle (SphereProjector) and listed in every 16x16 tile it touches; a tile tests its
// particles' path pieces against the rays of their rectangles (swept_sphere.h) and turns each ray's
// pieces into L and C_d (swept_absorption.h). Lists are built in particle order, so images do not
// depend on the thread count.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "render/volume/absorption.h"
#include "render/volume/screen_bins.h"
#include "render/volume/swept_absorption.h"
#include "render/volume/tile_rays.h"
#include "sim/core/vec.h"

namespace spume {

// How the diffuse particles move while the shutter is open.
struct DiffuseMotion {
  std::span<const Vec3f> velocities;  // m/s at the frame's time, one per particle
  double open = 0.0, close = 0.0;     // s, relative to the frame's time
  Vec3d gravity = Vec3d(0.0, -9.81, 0.0);
};

class SweptBins {
 public:
  static constexpr int kTile = ScreenBins::kTile;

  SweptBins(DiffuseView frame, const DiffuseMotion& motion, const std::array<float, kDiffuseTypeCount>& radius,
            const SphereProjector& projector, int width, int height);

  struct Entry {
    uint32_t particle;
    uint16_t x0, y0, x1, y1;  // pixels, inclusive, of the whole image
  };
  int tiles_x() const { return tiles_x_; }
  std::span<const Entry> tile(size_t t) const { return {entries_.data() + start_[t], entries_.data() + start_[t + 1]}; }
  const Aabb& bounds() const { return bounds_; }  // every swept sphere lies inside
  size_t particles() const { return particles_; }

 private:
  int tiles_x_ = 0, tiles_y_ = 0;
  std::vector<size_t> start_;
  std::vector<Entry> entries_;
  Aabb bounds_;
  size_t particles_ = 0;
};

struct SweptTraceScratch {
  std::vector<std::vector<SweptChord>> chords;  // per ray of the tile
  std::vector<uint8_t> wanted;
  SweptScratch absorb;
};

// Rays of the w x h tile at (x0, y0) that some listed path may touch (1 a ray, the rays' order).
const std::vector<uint8_t>& swept_candidates(const SweptBins& bins, int x0, int y0, int w, int h, int spp,
                                             SweptTraceScratch& s);

// L and C_d of the tile's rays `t`. Returns the number of path pieces met.
size_t trace_swept_tile(const TileRays& t, const SweptBins& bins, DiffuseView frame, const DiffuseMotion& motion,
                        const Vec3d& origin, const std::array<double, kDiffuseTypeCount>& r2, const VolumeShading& shading,
                        SweptTraceScratch& s, std::vector<RaySample>& out, std::vector<RayTypes>* types = nullptr);

}  // namespace spume

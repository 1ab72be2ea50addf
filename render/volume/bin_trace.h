#pragma once
// The exact integrator's trace over the screen bins (screen_bins.h): a bin's spheres are put in
// near-to-far order once, then each of its 16x16 tiles tests its spheres against the rays of their
// pixel rectangles and sums each ray's chords (absorption.h). Scratch memory is per worker thread.
#include <array>
#include <cstdint>
#include <vector>

#include "render/camera/camera.h"
#include "render/volume/absorption.h"
#include "render/volume/screen_bins.h"
#include "render/volume/tile_rays.h"

namespace spume {

struct BinScratch {
  std::vector<BinnedSphere> bin_sorted;      // the bin's spheres, near to far
  std::array<std::vector<BinnedSphere>, 4> tiles;  // those of each 16x16 tile (row-major), tile-relative
  std::vector<float> depth;
  std::vector<uint32_t> bucket, bucket_of;
  std::vector<uint32_t> ray_start, ray_end;  // per ray of the tile: its chords in `chords`
  std::vector<uint8_t> wanted;               // per ray of the tile: 1 when it has a candidate
  std::vector<Interval> chords;
  std::vector<double> ray_soa;               // the tile's rays as columns of doubles
};

// The bin [b, e) near to far, split into the lists of its 2x2 tiles (s.tiles).
void order_bin(const BinnedSphere* b, const BinnedSphere* e, const Camera& cam, BinScratch& s);

// The candidate spheres of each ray of the w x h tile at (ox, oy) pixels inside the bin last ordered
// by order_bin (spp rays a pixel), counted from their rectangles. Returns the tile's `wanted` mask:
// 1 for a ray some sphere may touch. A ray no sphere touches has no chord, so its sample is the
// empty one whatever surfaces it meets: make_tile_rays need not trace it.
const std::vector<uint8_t>& count_tile_candidates(int ox, int oy, int w, int h, int spp, BinScratch& s);

// Transmittance and colour of the tile's rays `t`, the tile at (ox, oy) whose candidates were
// counted last. origin: the camera position; r2: squared radius per type. With `types`, each ray's
// split by type too. Returns the number of chords found.
size_t trace_bin_tile(const TileRays& t, int ox, int oy, const Vec3d& origin, const std::array<double, kDiffuseTypeCount>& r2,
                      const VolumeShading& shading, BinScratch& s, std::vector<RaySample>& out,
                      std::vector<RayTypes>* types = nullptr);

}  // namespace spume

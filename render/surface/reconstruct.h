#pragma once
// Fluid particles -> a closed triangle mesh with smooth per-vertex normals (the surface the OSMesa pass
// draws as water).
//
// Method: drop isolated particles (fewer than min_neighbours others within h: spray, drawn by the
// volume pass), sample the smoothed colour field c(x) = sum V W_poly6(x - x_j, h) (about 1 in bulk) on a
// sparse lattice near the particles, and run marching cubes at c = iso. For a flat surface of a
// lattice at spacing 2r the continuous field of the half-space the particles fill (up to r beyond the
// outer centres) is exactly 1/2 at that half-space's boundary, so iso = 0.5 puts the surface at the
// particles' outer extent; with h = 4r the discrete lattice sum matches within 0.03 r (measured).
// A curved surface sits inward by about h^2 / (10 R) (mean curvature 1/R) -- see the tests. Then,
// optionally, Taubin smoothing takes out the particle lattice's bumps (mesh_smoothing.h).
#include <span>

#include "sim/core/vec.h"
#include "render/surface/triangle_mesh.h"
#include "render/keys/render_keys.h"
#include "sim/keys/scene_keys.h"

namespace spume {

struct SurfaceParams {
  float particle_radius = 0.0f;  // m, r (spacing 2r); required
  float support_factor = keys::fluid::kSupportFactor;  // kernel support h = factor * r, the fluid's (two spacings)
  float cell_factor = float(keys::render::surface_cell.value[0]);  // marching-cubes cell = factor * r
  float iso = 0.5f;              // iso-level as a fraction of the bulk colour (0.5: outer extent)
  int min_neighbours = 5;        // particles with fewer other particles within h are left out
  int smoothing = int(keys::render::surface_smoothing.value[0]);  // Taubin iterations (mesh_smoothing.h)

  // Throws Error for values out of range (naming `where`).
  void validate(const char* where) const;
};

struct SurfaceStats {
  size_t particles = 0;  // given
  size_t kept = 0;       // after leaving isolated ones out
  size_t bricks = 0;     // 8^3-point bricks sampled
  size_t vertices = 0, triangles = 0;
  double seconds_filter = 0, seconds_field = 0, seconds_mesh = 0, seconds_smooth = 0;
};

// Deterministic: the same mesh bytes for any thread count.
TriangleMesh reconstruct_surface(std::span<const Vec3f> positions, const SurfaceParams& params,
                                 SurfaceStats* stats = nullptr);

}  // namespace spume

#pragma once
// Smoothing of the reconstructed surface. Marching cubes over the colour field of particles on a
// lattice (a dropped block, a resting pool) reproduces the lattice: bumps one particle spacing apart
// that read as stair steps along edges and as a ripple in the shading. Taubin's lambda|mu smoothing
// (each iteration a shrinking umbrella step, lambda > 0, then an inflating one, mu < -lambda) damps such
// short wavelengths while leaving shapes many spacings across nearly where they were, so the surface
// neither shrinks nor drifts off the particles (measured by `spume report --only surface`). Normals
// are smoothed the same way, then renormalised.
#include <cstdint>
#include <vector>

#include "render/surface/triangle_mesh.h"

namespace spume {

// Each vertex's neighbours along the mesh's edges, ascending (compressed rows).
struct VertexNeighbours {
  std::vector<uint32_t> start;  // vertex count + 1 offsets into `index`
  std::vector<uint32_t> index;
};
VertexNeighbours vertex_neighbours(const TriangleMesh& mesh);

constexpr float kTaubinLambda = 0.5f, kTaubinMu = -0.53f;  // pass band about 0.1 of the edge frequency

// `iterations` lambda|mu pairs of umbrella steps on the positions. Deterministic for any thread count.
void smooth_positions(TriangleMesh& mesh, const VertexNeighbours& neighbours, int iterations);
// The same on the normals (a mesh without normals is left alone); each result is renormalised, and a
// normal whose neighbourhood cancels out keeps its old direction.
void smooth_normals(TriangleMesh& mesh, const VertexNeighbours& neighbours, int iterations);
// Both at once, the same values as smooth_positions then smooth_normals: one pass over the neighbour
// lists per step instead of two.
void smooth_surface(TriangleMesh& mesh, const VertexNeighbours& neighbours, int iterations);

}  // namespace spume

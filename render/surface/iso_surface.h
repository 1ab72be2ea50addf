#pragma once
// Marching cubes over a ColourField's sparse lattice: the closed iso-surface c = iso as an indexed
// triangle mesh with one vertex per crossing lattice edge (so neighbouring cells share vertices and
// the mesh is watertight) and normals from the field's analytic gradient at each vertex.
#include "render/surface/colour_field.h"
#include "render/surface/triangle_mesh.h"

namespace spume {

// iso must be > 0 (missing bricks are 0, which must read as outside). Triangles wind counter-clockwise
// seen from outside (where c < iso); normals point outward. Same bytes for any thread count.
TriangleMesh extract_iso_surface(const ColourField& field, float iso);

}  // namespace spume

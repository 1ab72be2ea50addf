#include "render/surface/reconstruct.h"

#include <cmath>

#include "render/surface/colour_field.h"
#include "sim/core/error.h"
#include "sim/core/stopwatch.h"
#include "render/surface/iso_surface.h"
#include "render/surface/isolated_particles.h"
#include "render/surface/mesh_smoothing.h"

namespace spume {

void SurfaceParams::validate(const char* where) const {
  auto positive = [&](float v, const char* name) {
    if (!(v > 0.0f) || !std::isfinite(v)) fail(where, ": ", name, " must be a positive number, got ", v);
  };
  positive(particle_radius, "particle radius");
  positive(support_factor, "support factor");
  positive(cell_factor, "cell factor");
  if (!(iso > 0.0f && iso < 1.0f))
    fail(where, ": iso-level must lie in (0, 1) (fraction of the bulk colour), got ", iso);
  if (support_factor < 2.0f)
    fail(where, ": support factor ", support_factor,
         " is below 2: the kernel would not reach the neighbours at spacing 2r");
  if (const std::string why = out_of_range(keys::render::surface_smoothing, smoothing); !why.empty())
    fail(where, ": smoothing iterations (", keys::render::surface_smoothing.path, "): ", why);
  if (cell_factor > support_factor)
    fail(where, ": cell factor ", cell_factor, " exceeds the support factor ", support_factor,
         ": cells larger than the kernel lose the surface");
}

TriangleMesh reconstruct_surface(std::span<const Vec3f> positions, const SurfaceParams& params, SurfaceStats* stats) {
  params.validate("surface");
  const float r = params.particle_radius, h = params.support_factor * r, cell = params.cell_factor * r;
  SurfaceStats s;
  s.particles = positions.size();

  Stopwatch t;
  const auto kept = connected_particles(positions, h, params.min_neighbours);
  std::vector<Vec3f> fluid;
  fluid.reserve(kept.size());
  for (uint32_t i : kept) fluid.push_back(positions[i]);
  s.kept = fluid.size();
  s.seconds_filter = t.seconds();

  t.restart();
  const ColourField field(fluid, r, h, cell);
  s.bricks = field.brick_count();
  s.seconds_field = t.seconds();

  t.restart();
  TriangleMesh mesh = extract_iso_surface(field, params.iso);
  s.vertices = mesh.vertices.size();
  s.triangles = mesh.triangle_count();
  s.seconds_mesh = t.seconds();

  if (params.smoothing > 0) {
    t.restart();
    const VertexNeighbours neighbours = vertex_neighbours(mesh);
    smooth_surface(mesh, neighbours, params.smoothing);
    s.seconds_smooth = t.seconds();
  }
  if (stats) *stats = s;
  return mesh;
}

}  // namespace spume

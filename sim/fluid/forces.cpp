#include "sim/fluid/forces.h"

#include "sim/core/parallel.h"
#include "sim/core/cubic_spline.h"

namespace spume::fluid {

void non_pressure_accelerations(const FluidSolverParams& params, const Neighbourhoods& nb, const Boundary& boundary,
                                float h, float volume, double dt, Particles& p) {
  const size_t n = p.size();
  const Vec3f g = params.gravity;
  const float nu = 10.0f * params.viscosity, nu_b = 10.0f * params.boundary_viscosity;  // 2 (d + 2) nu
  const float soften = 0.01f * h * h;  // keeps the term finite for coincident particles
  const float xsph = params.xsph / float(dt);
  const CubicSpline kernel(h);
  if (nu == 0.0f && nu_b == 0.0f && xsph == 0.0f) {
    parallel_for(n, 4096, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) p.accel[i] = g;
    });
    return;
  }
  std::span<const Vec3f> bx = boundary.grid.sorted_points();
  parallel_for(n, 512, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const Vec3f xi = p.x[i], vi = p.v[i];
      Vec3f a = Vec3f::Zero();
      if (nu > 0.0f)
        for (uint32_t k = nb.offset[i]; k < nb.offset[i + 1]; ++k) {
          const FluidPair q = nb.pairs[k];
          const Vec3f xij = xi - p.x[q.j];
          // q.g = V grad W_ij, so m_j / rho_j grad W_ij = q.g / (rho_j / rho0).
          a += (nu * (vi - p.v[q.j]).dot(xij) / ((xij.squaredNorm() + soften) * p.density[q.j])) * q.g(xij);
        }
      if (xsph > 0.0f)
        for (uint32_t k = nb.offset[i]; k < nb.offset[i + 1]; ++k) {
          const FluidPair q = nb.pairs[k];
          const float w = kernel.value((xi - p.x[q.j]).norm());
          a += (xsph * volume * w / p.density[q.j]) * (p.v[q.j] - vi);
        }
      if (nu_b > 0.0f) {
        const float inv_rho = 1.0f / p.density[i];
        for (uint32_t k = nb.boundary_offset[i]; k < nb.boundary_offset[i + 1]; ++k) {
          const Pair q = nb.boundary_pairs[k];
          const Vec3f xib = xi - bx[q.j];
          a += (nu_b * (vi - boundary.sorted_velocity[q.j]).dot(xib) / (xib.squaredNorm() + soften) * inv_rho) * q.g();
        }
      }
      p.accel[i] = g + a;
    }
  });
}

}  // namespace spume::fluid

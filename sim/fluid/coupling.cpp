#include "sim/fluid/coupling.h"

#include <algorithm>

#include "sim/core/parallel.h"
#include "sim/fluid/reduce.h"

namespace spume::fluid {
namespace {

// Sums fn(i, add) over the fluid particles into per-body (linear, angular) pairs: chunks of
// kReduceChunk particles in parallel, each in index order, then the chunks in order. `add(body,
// lever_point, vector)` records `vector` for `body` acting at `lever_point`.
template <typename Fn>
void sum_over_bodies(size_t n, const CouplingBodies& bodies, std::vector<Vec3d>& linear,
                     std::vector<Vec3d>& angular, Fn&& fn) {
  const size_t m = bodies.centre.size();
  if (m == 0 || n == 0) return;
  const size_t chunks = (n + kReduceChunk - 1) / kReduceChunk;
  std::vector<Vec3d> part_l(chunks * m, Vec3d::Zero()), part_a(chunks * m, Vec3d::Zero());
  parallel_for(chunks, 1, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c) {
      Vec3d* l = &part_l[c * m];
      Vec3d* a = &part_a[c * m];
      auto add = [&](int body, const Vec3f& at, const Vec3f& v) {
        const Vec3d vd = v.cast<double>();
        l[body] += vd;
        a[body] += (at - bodies.centre[size_t(body)]).cast<double>().cross(vd);
      };
      for (size_t i = c * kReduceChunk; i < std::min(n, (c + 1) * kReduceChunk); ++i) fn(i, add);
    }
  });
  for (size_t c = 0; c < chunks; ++c)
    for (size_t k = 0; k < m; ++k) {
      linear[k] += part_l[c * m + k];
      angular[k] += part_a[c * m + k];
    }
}

}  // namespace

void BodyLoads::reset(size_t bodies) {
  impulse.assign(bodies, Vec3d::Zero());
  angular_impulse.assign(bodies, Vec3d::Zero());
  force.assign(bodies, Vec3d::Zero());
  torque.assign(bodies, Vec3d::Zero());
}

void BodyLoads::totals(double dt, std::vector<Vec3d>& f, std::vector<Vec3d>& t) const {
  f.resize(impulse.size());
  t.resize(impulse.size());
  for (size_t k = 0; k < impulse.size(); ++k) {
    f[k] = impulse[k] / dt + force[k];
    t[k] = angular_impulse[k] / dt + torque[k];
  }
}

void add_pressure_impulse(const Neighbourhoods& nb, const Boundary& boundary, const WallPressure* walls,
                          const CouplingBodies& bodies, float particle_mass, double dt_s, const Particles& p,
                          BodyLoads& loads) {
  std::span<const Vec3f> bx = boundary.grid.sorted_points();
  const float scale = float(double(particle_mass) * dt_s);
  sum_over_bodies(p.size(), bodies, loads.impulse, loads.angular_impulse, [&](size_t i, auto& add) {
    const float k = p.source[i];
    if (!walls && k == 0.0f) return;  // nothing pushed this particle's walls
    for (uint32_t e = nb.boundary_offset[i]; e < nb.boundary_offset[i + 1]; ++e) {
      const Pair q = nb.boundary_pairs[e];
      const int body = bodies.body_of_solid[boundary.sorted_solid[q.j]];
      const float k_pair = walls ? k + walls->total[q.j] : k;  // as apply_pressure pushed the particle
      if (body >= 0 && k_pair != 0.0f) add(body, bx[q.j], Vec3f((scale * k_pair) * q.g()));
    }
  });
}

void add_viscous_force(const FluidSolverParams& params, const Neighbourhoods& nb, const Boundary& boundary,
                       const CouplingBodies& bodies, float particle_mass, float h, const Particles& p,
                       BodyLoads& loads) {
  const float nu_b = 10.0f * params.boundary_viscosity;  // 2 (d + 2) nu, as in forces.cpp
  if (nu_b == 0.0f) return;
  const float soften = 0.01f * h * h;
  std::span<const Vec3f> bx = boundary.grid.sorted_points();
  sum_over_bodies(p.size(), bodies, loads.force, loads.torque, [&](size_t i, auto& add) {
    const Vec3f xi = p.x[i], vi = p.v[i];
    const float inv_rho = 1.0f / p.density[i];
    for (uint32_t e = nb.boundary_offset[i]; e < nb.boundary_offset[i + 1]; ++e) {
      const Pair q = nb.boundary_pairs[e];
      const int body = bodies.body_of_solid[boundary.sorted_solid[q.j]];
      if (body < 0) continue;
      const Vec3f xib = xi - bx[q.j];
      const Vec3f a = (nu_b * (vi - boundary.sorted_velocity[q.j]).dot(xib) / (xib.squaredNorm() + soften) * inv_rho) * q.g();
      add(body, bx[q.j], Vec3f(-particle_mass * a));
    }
  });
}

}  // namespace spume::fluid

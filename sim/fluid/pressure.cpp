#include "sim/fluid/pressure.h"

#include <algorithm>
#include <cmath>

#include "sim/core/parallel.h"
#include "sim/fluid/lanes.h"
#include "sim/fluid/reduce.h"

namespace spume::fluid {
namespace {

// Fraction of the previous step's pressure a warm-started solve begins with (as in SPlisHSPlasH).
constexpr float kWarmStartFraction = 0.5f;

// The divergence-free solve leaves out particles whose density is below this fraction of rho0: at a
// free surface the neighbourhood is too thin for a meaningful divergence, and correcting it there
// pulls the surface together (the role of SPlisHSPlasH's neighbour-count test).
constexpr float kDivergenceMinDensity = 0.8f;

// sum_b v_b . V_b grad W_ib, zero unless a solid moves. Constant during a solve.
std::vector<float> boundary_flux(const Neighbourhoods& nb, const Boundary& boundary, const Particles& p) {
  std::vector<float> flux;
  if (!boundary.any_moving) return flux;
  const size_t n = p.size();
  flux.assign(n, 0.0f);
  parallel_for(n, 1024, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      float s = 0.0f;
      for (uint32_t k = nb.boundary_offset[i]; k < nb.boundary_offset[i + 1]; ++k) {
        const Pair q = nb.boundary_pairs[k];
        s += boundary.sorted_velocity[q.j].dot(q.g());
      }
      flux[i] = s;
    }
  });
  return flux;
}

// (D rho_i / Dt) / rho0 = sum_j V_j (v_i - v_j) . grad W_ij + sum_b V_b (v_i - v_b) . grad W_ib
// (the continuity equation discretised as in [BK17], with the boundary term of [AIA12]), 1/s. Reads
// the padded copies p.x4, p.v4 (lanes.h): each pair's x, y, z in one vector operation.
inline float density_rate(const Neighbourhoods& nb, const std::vector<float>& flux, const Particles& p, size_t i) {
  const Lanes xi = Lanes::load(p.x4[i]), vi = Lanes::load(p.v4[i]);
  float s = 0.0f;
  for (uint32_t k = nb.offset[i]; k < nb.offset[i + 1]; ++k) {
    const FluidPair q = nb.pairs[k];
    const Lanes g = Lanes::splat(q.s) * (xi - Lanes::load(p.x4[q.j]));
    s += (g * (vi - Lanes::load(p.v4[q.j]))).sum3();
  }
  s += p.v4[i].vec().dot(nb.boundary_grad[i]);
  if (!flux.empty()) s -= flux[i];
  return s;
}

// One Jacobi velocity update of p.v4 with the pressure increments in p.pressure ([BK17], pressure/mass = k).
// p.x4[j]'s fourth lane must hold -k_j: then (x_i, k_i) - (x_j, -k_j) gives x_i - x_j and, exactly,
// k_i + k_j (IEEE a - (-b) is a + b) from one load a neighbour.
void apply_pressure(const Neighbourhoods& nb, float dt, Particles& p) {
  parallel_for(p.size(), 512, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const float ki = p.pressure[i];
      const Lanes xi = Lanes::with_w(p.x4[i], ki);
      Lanes a = Lanes::zero();
      for (uint32_t k = nb.offset[i]; k < nb.offset[i + 1]; ++k) {
        const FluidPair q = nb.pairs[k];
        const Lanes d = xi - Lanes::load(p.x4[q.j]);  // (x_i - x_j, k_i + k_j)
        a = a + d.broadcast_w() * (Lanes::splat(q.s) * d);
      }
      const Lanes v = Lanes::load(p.v4[i]) - Lanes::splat(dt) * (a.xyz() + Lanes::splat(ki) * Lanes::of(nb.boundary_grad[i]));
      v.store(p.v4[i]);
    }
  });
}

// Jacobi loop shared by both solves ([BK17]: divergence-free and constant-density solvers). `residual(i)` returns particle i's
// residual from the current velocities (compression > 0), or NaN for a particle the solve leaves
// out. Only compression is corrected: k_i = max(residual, 0) alpha_i scale (Eqs. 12, 14 in [BK17]).
// The error is the mean clamped residual over all particles times error_scale. The loop is:
// residual, then (update velocities, residual) until the error is small, so the reported error is
// that of the final velocities.
template <typename Residual>
SolveResult jacobi(const FluidSolverParams& params, const Neighbourhoods& nb, int min_iterations, int max_iterations,
                   float tolerance, double error_scale, float scale, double warm_scale, float dt,
                   std::vector<float>& warm, Particles& p, Residual&& residual) {
  const size_t n = p.size();
  std::vector<float>& total = p.source;  // pressure applied so far in this solve
  auto residual_pass = [&]() {
    const double sum = chunked_sum(n, [&](size_t b, size_t e) {
      double s = 0.0;
      for (size_t i = b; i < e; ++i) {
        const float r = residual(i);
        const float c = std::isnan(r) ? 0.0f : std::max(r, 0.0f);
        p.pressure[i] = c * p.factor[i] * scale;
        s += c;
      }
      return s;
    });
    return n ? sum / double(n) * error_scale : 0.0;
  };
  auto apply = [&]() {
    parallel_for(n, 4096, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) {
        total[i] += p.pressure[i];
        p.x4[i].c[3] = -p.pressure[i];  // what apply_pressure reads for a neighbour
      }
    });
    apply_pressure(nb, dt, p);
  };
  std::fill(total.begin(), total.end(), 0.0f);
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      p.x4[i] = Padded3(p.x[i]);
      p.v4[i] = Padded3(p.v[i]);
    }
  });
  double error = residual_pass();
  if (params.warm_start) {
    // Re-apply part of the last step's pressure where the fluid is compressed now (warm start, [BK17]).
    parallel_for(n, 4096, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i)
        p.pressure[i] = p.pressure[i] > 0.0f ? float(kWarmStartFraction * warm[i] * warm_scale) : 0.0f;
    });
    apply();
    error = residual_pass();
  }
  SolveResult result;
  while ((error > tolerance || result.iterations < min_iterations) && result.iterations < max_iterations) {
    apply();
    ++result.iterations;
    error = residual_pass();
  }
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) p.v[i] = p.v4[i].vec();
  });
  if (params.warm_start)
    parallel_for(n, 4096, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) warm[i] = float(total[i] / warm_scale);
    });
  result.error = error;
  result.converged = error <= tolerance;
  return result;
}

}  // namespace

SolveResult divergence_solve(const FluidSolverParams& params, const Neighbourhoods& nb, const Boundary& boundary,
                             double dt, Particles& p) {
  const std::vector<float> flux = boundary_flux(nb, boundary, p);
  auto residual = [&](size_t i) {
    return p.density[i] >= kDivergenceMinDensity ? density_rate(nb, flux, p, i) : NAN;
  };
  // Residual: compression rate (1/s); pressure k = rate alpha / dt; error: mean rate * dt; stored k dt.
  return jacobi(params, nb, params.min_divergence_iterations, params.max_divergence_iterations,
                params.divergence_tolerance, dt, float(1.0 / dt), 1.0 / dt, float(dt), p.divergence_warm, p,
                residual);
}

SolveResult density_solve(const FluidSolverParams& params, const Neighbourhoods& nb, const Boundary& boundary,
                          double dt, Particles& p) {
  const std::vector<float> flux = boundary_flux(nb, boundary, p);
  const float fdt = float(dt);
  // Residual: rho*_i / rho0 - 1 ([BK17]); pressure k = residual alpha / dt^2; stored k dt^2.
  auto residual = [&](size_t i) { return p.density[i] + fdt * density_rate(nb, flux, p, i) - 1.0f; };
  return jacobi(params, nb, params.min_density_iterations, params.max_density_iterations, params.density_tolerance,
                1.0, float(1.0 / (dt * dt)), 1.0 / (dt * dt), fdt, p.density_warm, p, residual);
}

}  // namespace spume::fluid

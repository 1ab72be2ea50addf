#include "sim/fluid/pressure.h"

#include <algorithm>
#include <cmath>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "sim/core/parallel.h"
#include "sim/fluid/fused_sweep.h"
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

// One pair's term of the density rate: V_j grad W_ij * (v_i - v_j), in x, y, z.
inline Lanes rate_term(const Particles& p, const FluidPair& q, Lanes xi, Lanes vi) {
  return (Lanes::splat(q.s) * (xi - Lanes::load(p.x4[q.j]))) * (vi - Lanes::load(p.v4[q.j]));
}

// One pair's pressure term with xi = (x_i, k_i): (k_i + k_j) V_j grad W_ij in x, y, z (apply_pressure).
inline Lanes pressure_term(const Particles& p, const FluidPair& q, Lanes xi) {
  const Lanes d = xi - Lanes::load(p.x4[q.j]);  // (x_i - x_j, k_i + k_j)
  return d.broadcast_w() * (Lanes::splat(q.s) * d);
}

#if defined(__x86_64__)
const bool kHasAvx2 = __builtin_cpu_supports("avx2");

// The pair sums below on processors with AVX2: two pairs a 256-bit vector, pair k + 1 in the upper
// half, so the running sums (k mod 4 = 0 | 1) and (2 | 3) are PartialSums' four sums in pairs of
// halves, the leftover pairs go to the sums PartialSums gives them, and the four are added in its
// order: every lane does the IEEE operations the SSE2 path does, and the results are the same bits.
__attribute__((target("avx2"))) inline __m256 both_halves(const Padded3& low, const Padded3& high) {
  return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(low.c)), _mm_load_ps(high.c), 1);
}
__attribute__((target("avx2"))) inline __m256 splat_halves(float low, float high) {
  return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_set1_ps(low)), _mm_set1_ps(high), 1);
}
__attribute__((target("avx2"))) inline Lanes total_of(__m256 a, __m256 b, PartialSums& sums) {
  sums.s[0] = sums.s[0] + Lanes{_mm256_castps256_ps128(a)};
  sums.s[1] = sums.s[1] + Lanes{_mm256_extractf128_ps(a, 1)};
  sums.s[2] = sums.s[2] + Lanes{_mm256_castps256_ps128(b)};
  sums.s[3] = sums.s[3] + Lanes{_mm256_extractf128_ps(b, 1)};
  return sums.total();
}

__attribute__((target("avx2"))) Lanes rate_pairs_avx2(const Neighbourhoods& nb, const Particles& p, size_t i) {
  const Lanes xi = Lanes::load(p.x4[i]), vi = Lanes::load(p.v4[i]);
  const __m256 xi2 = _mm256_set_m128(xi.m, xi.m), vi2 = _mm256_set_m128(vi.m, vi.m);
  __m256 a = _mm256_setzero_ps(), b = _mm256_setzero_ps();
  uint32_t k = nb.offset[i];
  const uint32_t end = nb.offset[i + 1];
  for (; k + kPartialSums <= end; k += kPartialSums) {
    const FluidPair* q = &nb.pairs[k];
    const __m256 g01 = _mm256_mul_ps(splat_halves(q[0].s, q[1].s), _mm256_sub_ps(xi2, both_halves(p.x4[q[0].j], p.x4[q[1].j])));
    a = _mm256_add_ps(a, _mm256_mul_ps(g01, _mm256_sub_ps(vi2, both_halves(p.v4[q[0].j], p.v4[q[1].j]))));
    const __m256 g23 = _mm256_mul_ps(splat_halves(q[2].s, q[3].s), _mm256_sub_ps(xi2, both_halves(p.x4[q[2].j], p.x4[q[3].j])));
    b = _mm256_add_ps(b, _mm256_mul_ps(g23, _mm256_sub_ps(vi2, both_halves(p.v4[q[2].j], p.v4[q[3].j]))));
  }
  PartialSums sums;
  sums.add_pairs(k, end, [&](uint32_t r) { return rate_term(p, nb.pairs[r], xi, vi); });
  return total_of(a, b, sums);
}

__attribute__((target("avx2"))) Lanes pressure_pairs_avx2(const Neighbourhoods& nb, const Particles& p, size_t i,
                                                          Lanes xi) {
  const __m256 xi2 = _mm256_set_m128(xi.m, xi.m);
  __m256 a = _mm256_setzero_ps(), b = _mm256_setzero_ps();
  uint32_t k = nb.offset[i];
  const uint32_t end = nb.offset[i + 1];
  for (; k + kPartialSums <= end; k += kPartialSums) {
    const FluidPair* q = &nb.pairs[k];
    const __m256 d01 = _mm256_sub_ps(xi2, both_halves(p.x4[q[0].j], p.x4[q[1].j]));
    a = _mm256_add_ps(a, _mm256_mul_ps(_mm256_shuffle_ps(d01, d01, 0xff), _mm256_mul_ps(splat_halves(q[0].s, q[1].s), d01)));
    const __m256 d23 = _mm256_sub_ps(xi2, both_halves(p.x4[q[2].j], p.x4[q[3].j]));
    b = _mm256_add_ps(b, _mm256_mul_ps(_mm256_shuffle_ps(d23, d23, 0xff), _mm256_mul_ps(splat_halves(q[2].s, q[3].s), d23)));
  }
  PartialSums sums;
  sums.add_pairs(k, end, [&](uint32_t r) { return pressure_term(p, nb.pairs[r], xi); });
  return total_of(a, b, sums);
}
#endif

// sum_j V_j (v_i - v_j) . grad W_ij as a vector of the x, y, z terms, from the padded copies p.x4,
// p.v4 (lanes.h): each pair's x, y, z in one vector operation. The pairs are summed into
// kPartialSums vector sums, pair k into sum k mod kPartialSums (lanes.h), so that the additions of
// consecutive pairs do not wait on each other; the order depends on the pair list only.
inline Lanes rate_pairs(const Neighbourhoods& nb, const Particles& p, size_t i) {
#if defined(__x86_64__)
  if (kHasAvx2) return rate_pairs_avx2(nb, p, i);
#endif
  const Lanes xi = Lanes::load(p.x4[i]), vi = Lanes::load(p.v4[i]);
  PartialSums sums;
  sums.add_pairs(nb.offset[i], nb.offset[i + 1], [&](uint32_t k) { return rate_term(p, nb.pairs[k], xi, vi); });
  return sums.total();
}

// sum_j (k_i + k_j) V_j grad W_ij in x, y, z, with xi = (x_i, k_i); see apply_pressure.
inline Lanes pressure_pairs(const Neighbourhoods& nb, const Particles& p, size_t i, Lanes xi) {
#if defined(__x86_64__)
  if (kHasAvx2) return pressure_pairs_avx2(nb, p, i, xi);
#endif
  PartialSums sums;
  sums.add_pairs(nb.offset[i], nb.offset[i + 1], [&](uint32_t k) { return pressure_term(p, nb.pairs[k], xi); });
  return sums.total();
}

// (D rho_i / Dt) / rho0 = sum_j V_j (v_i - v_j) . grad W_ij + sum_b V_b (v_i - v_b) . grad W_ib
// (the continuity equation discretised as in [BK17], with the boundary term of [AIA12]), 1/s.
inline float density_rate(const Neighbourhoods& nb, const std::vector<float>& flux, const Particles& p, size_t i) {
  float s = rate_pairs(nb, p, i).sum3();
  s += p.v4[i].vec().dot(nb.boundary_grad[i]);
  if (!flux.empty()) s -= flux[i];
  return s;
}

// One Jacobi velocity update of p.v4[b, e) with the pressure increments in p.pressure ([BK17], pressure/mass = k).
// p.x4[j]'s fourth lane must hold -k_j: then (x_i, k_i) - (x_j, -k_j) gives x_i - x_j and, exactly,
// k_i + k_j (IEEE a - (-b) is a + b) from one load a neighbour.
void apply_pressure(const Neighbourhoods& nb, const WallPressure* walls, float dt, Particles& p, size_t b, size_t e) {
  for (size_t i = b; i < e; ++i) {
    const float ki = p.pressure[i];
    const Lanes a = pressure_pairs(nb, p, i, Lanes::with_w(p.x4[i], ki));
    // sum_b (k_i + k_b) V_b grad W_ib, with k_b = 0 unless the walls' pressure is extrapolated.
    Vec3f wall = ki * nb.boundary_grad[i];
    if (walls)
      for (uint32_t k = nb.boundary_offset[i]; k < nb.boundary_offset[i + 1]; ++k) {
        const Pair q = nb.boundary_pairs[k];
        wall += walls->k[q.j] * q.g();
      }
    const Lanes v = Lanes::load(p.v4[i]) - Lanes::splat(dt) * (a.xyz() + Lanes::of(wall));
    v.store(p.v4[i]);
  }
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
                   std::vector<float>& warm, Particles& p, WallPressure* walls, float rise_scale, Residual&& residual) {
  const size_t n = p.size();
  std::vector<float>& total = p.source;  // pressure applied so far in this solve
  // The new pressures of particles [b, e) from the current velocities; returns their summed residual.
  auto residual_range = [&](size_t b, size_t e) {
    double s = 0.0;
    for (size_t i = b; i < e; ++i) {
      const float r = residual(i);
      const float c = std::isnan(r) ? 0.0f : std::max(r, 0.0f);
      p.pressure[i] = c * p.factor[i] * scale;
      s += c;
    }
    return s;
  };
  auto mean_error = [&](double sum) { return n ? sum / double(n) * error_scale : 0.0; };
  auto residual_pass = [&]() { return mean_error(chunked_sum(n, residual_range)); };
  // Applies the pressures, then returns the residual pass's error, in one sweep (fused_sweep.h).
  const std::vector<Neighbourhoods::Reach> reach = chunk_reach(nb);
  auto apply_then_residual = [&]() {
    parallel_for(n, 4096, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) {
        total[i] += p.pressure[i];
        p.x4[i].c[3] = -p.pressure[i];  // what apply_pressure reads for a neighbour
      }
    });
    if (walls) {
      walls->extrapolate(p.pressure, rise_scale);
      rise_scale = 0.0f;
    }
    return mean_error(
        fused_sweep(n, reach, [&](size_t b, size_t e) { apply_pressure(nb, walls, dt, p, b, e); }, residual_range));
  };
  std::fill(total.begin(), total.end(), 0.0f);
  if (walls) std::fill(walls->total.begin(), walls->total.end(), 0.0f);
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
    error = apply_then_residual();
  }
  SolveResult result;
  while ((error > tolerance || result.iterations < min_iterations) && result.iterations < max_iterations) {
    error = apply_then_residual();
    ++result.iterations;
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
                             double dt, Particles& p, WallPressure* walls) {
  const std::vector<float> flux = boundary_flux(nb, boundary, p);
  auto residual = [&](size_t i) {
    return p.density[i] >= kDivergenceMinDensity ? density_rate(nb, flux, p, i) : NAN;
  };
  // Residual: compression rate (1/s); pressure k = rate alpha / dt; error: mean rate * dt; stored k dt.
  return jacobi(params, nb, params.min_divergence_iterations, params.max_divergence_iterations,
                params.divergence_tolerance, dt, float(1.0 / dt), 1.0 / dt, float(dt), p.divergence_warm, p,
                walls, 0.0f, residual);
}

SolveResult density_solve(const FluidSolverParams& params, const Neighbourhoods& nb, const Boundary& boundary,
                          double dt, Particles& p, WallPressure* walls) {
  const std::vector<float> flux = boundary_flux(nb, boundary, p);
  const float fdt = float(dt);
  // Residual: rho*_i / rho0 - 1 ([BK17]); pressure k = residual alpha / dt^2; stored k dt^2.
  auto residual = [&](size_t i) { return p.density[i] + fdt * density_rate(nb, flux, p, i) - 1.0f; };
  return jacobi(params, nb, params.min_density_iterations, params.max_density_iterations, params.density_tolerance,
                1.0, float(1.0 / (dt * dt)), 1.0 / (dt * dt), fdt, p.density_warm, p, walls, 1.0f, residual);
}

}  // namespace spume::fluid

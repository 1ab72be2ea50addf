// Fluid solver throughput: the dam break of SPlisHSPlasH's reference measurement, ~30k
// particles of radius 0.02 m (a 1 x 2 x 1 m column, 25 x 50 x 25 = 31,250 particles, in a 4 x 3 x 1 m
// tank), simulated for 1 s at 50 frames per second from rest. Reported per repetition:
// microseconds per particle-step (wall time / (steps x particles)), average time step, steps per
// frame, iterations, and the share of each stage. A second case runs the same scene at r = 10.4 mm
// (48 x 96 x 48 = 221,184 particles; takes minutes), and a third at the paper's size, r = 7.25 mm
// (68 x 137 x 68 = 633,488 particles, the lighthouse's 640k), for its first 0.1 s only (about a minute).
// (At r = 7.3 mm, 68 x 136 x 68, the solver blows up at t = 0.068 s. 7.25 mm passes the blow-up check
// but is not right: a particle squeezed into a vertical edge of the tank runs up it at 17 m/s. Both
// run healthy with max_dt 1 ms and the extrapolated wall pressure: README, Deep fluid against walls.
// The case measures the solver's speed at this size, with the defaults.)
// Anchor: SPlisHSPlasH 2.16 DFSPH on this machine,
// 52.5 ms per step = 1.7 us per particle-step, average dt 2.57 ms. Target: <= 1.5 us.
// Run: build/bench/bench_fluid --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (one case: --benchmark_filter='BM_DamBreak/7250/')
#include <benchmark/benchmark.h>

#include <chrono>

#include "sim/core/parallel.h"
#include "sim/fluid/solver.h"

namespace spume {
namespace {

FluidSolver dam_break(float radius) {
  FluidSolverParams p;
  p.particle_radius = radius;
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(0, 0, 0);
  tank.max = Vec3f(4, 3, 1);
  return FluidSolver(p, {FluidBlock{Vec3f(0, 0, 0), Vec3f(1, 2, 1)}}, SolidSet({tank}));
}

void BM_DamBreak(benchmark::State& state) {
  const float radius = float(state.range(0)) * 1e-6f;
  const int frames = int(state.range(1));
  set_thread_count(0);
  double seconds = 0.0, particle_steps = 0.0;
  SolverStats st;
  for (auto _ : state) {
    state.PauseTiming();
    FluidSolver solver = dam_break(radius);
    state.ResumeTiming();
    const auto t0 = std::chrono::steady_clock::now();
    for (int f = 1; f <= frames; ++f) solver.advance_to(f / 50.0);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    st = solver.stats();
    particle_steps += double(st.steps) * double(solver.size());
    state.counters["particles"] = double(solver.size());
  }
  state.counters["us_per_particle_step"] = 1e6 * seconds / particle_steps;
  state.counters["avg_dt_ms"] = 1e3 * st.average_dt;
  state.counters["steps_per_frame"] = double(st.steps) / frames;
  state.counters["density_iterations"] = st.average_density_iterations;
  state.counters["divergence_iterations"] = st.average_divergence_iterations;
  state.counters["ms_per_frame"] = 1e3 * seconds / (double(state.iterations()) * frames);
  double stage_total = 0.0;
  for (double s : st.stage_seconds) stage_total += s;
  const char* names[] = {"neighbours_pct", "divergence_pct", "forces_pct", "density_pct", "advect_pct"};
  for (size_t s = 0; s < st.stage_seconds.size(); ++s) state.counters[names[s]] = 100.0 * st.stage_seconds[s] / stage_total;
}

// radius in micrometres, frames at 50 fps.
BENCHMARK(BM_DamBreak)->Args({20000, 50})->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_DamBreak)->Args({10400, 50})->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_DamBreak)->Args({7250, 5})->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace spume

BENCHMARK_MAIN();

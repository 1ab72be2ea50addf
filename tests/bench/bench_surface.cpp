// Surface stage throughput. Reconstruction on a dam-break-like block: jittered lattice
// particles (r = 0.01 m) whose top follows a wave, plus a few spray stragglers above it; about 220k and
// 640k particles; median wall time and triangle count, split by stage. Then the OSMesa surface pass
// drawing the 220k block's surface in a tank at 1920x1080.
// Run: build/bench/bench_surface --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Anchor: splashsurf reconstructs 13.4M particles in 2.5 s on 14 cores.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "render/gl/surface_pass.h"
#include "render/surface/mesh_primitives.h"
#include "render/surface/reconstruct.h"

namespace spume {
namespace {

constexpr float kRadius = 0.01f, kSpacing = 2 * kRadius;

std::vector<Vec3f> dam_block(int nx, int ny, int nz) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> jitter(-0.1f * kSpacing, 0.1f * kSpacing), u(0.0f, 1.0f);
  std::vector<Vec3f> p;
  p.reserve(size_t(nx) * ny * nz + 2000);
  const float depth = ny * kSpacing;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const float x = i * kSpacing, z = k * kSpacing;
        const float top =
            depth + 0.06f * std::sin(5.0f * x) * std::cos(4.0f * z) + 0.03f * std::sin(11.0f * z + 2.0f * x);
        p.emplace_back(x + jitter(rng), (j + 0.5f) * kSpacing * top / depth + jitter(rng), z + jitter(rng));
      }
  for (int i = 0; i < 2000; ++i)  // spray: left out by the neighbour filter
    p.emplace_back(u(rng) * nx * kSpacing, depth + 0.1f + 0.3f * u(rng), u(rng) * nz * kSpacing);
  return p;
}

void BM_Reconstruct(benchmark::State& state) {
  const int nx = int(state.range(0)), ny = int(state.range(1)), nz = int(state.range(2));
  const auto particles = dam_block(nx, ny, nz);
  SurfaceParams params;
  params.particle_radius = kRadius;
  params.cell_factor = float(state.range(3)) / 100.0f;
  SurfaceStats stats;
  for (auto _ : state) benchmark::DoNotOptimize(reconstruct_surface(particles, params, &stats));
  state.counters["particles"] = double(particles.size());
  state.counters["triangles"] = double(stats.triangles);
  state.counters["bricks"] = double(stats.bricks);
  state.counters["filter_ms"] = 1e3 * stats.seconds_filter;
  state.counters["field_ms"] = 1e3 * stats.seconds_field;
  state.counters["mesh_ms"] = 1e3 * stats.seconds_mesh;
  state.counters["smooth_ms"] = 1e3 * stats.seconds_smooth;
}

// Args: particles along x, y, z; cell size in hundredths of r.
BENCHMARK(BM_Reconstruct)
    ->Args({110, 20, 100, 100})  // 220k, cell r (default)
    ->Args({160, 25, 160, 100})  // 640k, cell r
    ->Args({110, 20, 100, 50})   // 220k, cell r/2
    ->Args({160, 25, 160, 50})   // 640k, cell r/2
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Arg: supersampling factor.
void BM_SurfacePass(benchmark::State& state) {
  static const TriangleMesh fluid = [] {
    SurfaceParams params;
    params.particle_radius = kRadius;
    return reconstruct_surface(dam_block(110, 20, 100), params);
  }();
  static const TriangleMesh tank = [] {
    TriangleMesh t;
    t.append(make_box_mesh(Vec3f(-0.05f, -0.05f, -0.05f), Vec3f(2.25f, 0.0f, 2.05f)));
    t.append(make_box_mesh(Vec3f(-0.05f, 0.0f, -0.05f), Vec3f(0.0f, 0.6f, 2.05f)));
    t.append(make_box_mesh(Vec3f(2.2f, 0.0f, -0.05f), Vec3f(2.25f, 0.6f, 2.05f)));
    t.append(make_box_mesh(Vec3f(0.0f, 0.0f, -0.05f), Vec3f(2.2f, 0.6f, 0.0f)));
    return t;
  }();
  SurfaceScene scene;
  scene.fluid = &fluid;
  scene.solids.push_back({&tank, Vec3f(0.7f, 0.7f, 0.72f), Vec3f::Zero()});
  scene.environment.ground_height = -0.05f;
  Camera cam;
  cam.position = Vec3f(1.1f, 1.4f, 3.6f), cam.target = Vec3f(1.1f, 0.2f, 0.9f), cam.fov_y_degrees = 50;
  cam.width = 1920, cam.height = 1080;
  // One pass (and GL context) per run, destroyed within it: two static passes, destroyed at program
  // exit, crashed the benchmark there (segfault after the results were printed).
  SurfacePass pass(SurfacePassOptions{.supersample = int(state.range(0)), .gl = {}});
  SurfacePassStats stats;
  for (auto _ : state) benchmark::DoNotOptimize(pass.render(scene, cam, &stats));
  state.counters["triangles"] = double(stats.triangles);
  state.counters["upload_ms"] = 1e3 * stats.seconds_upload;
  state.counters["shadow_ms"] = 1e3 * stats.seconds_shadow;
  state.counters["opaque_ms"] = 1e3 * stats.seconds_opaque;
  state.counters["water_back_ms"] = 1e3 * stats.seconds_water_back;
  state.counters["water_front_ms"] = 1e3 * stats.seconds_water_front;
  state.counters["resolve_ms"] = 1e3 * stats.seconds_resolve;
  state.counters["readback_ms"] = 1e3 * stats.seconds_readback;
}
BENCHMARK(BM_SurfacePass)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace spume

BENCHMARK_MAIN();

// Volume pass on a dense synthetic box: N spheres uniform in the unit cube,
// r = 0.35 N^(-1/3), 1920x1080, 1 sample per pixel, camera 1.2 m from the cube's centre (about
// 97% of the rays cross the box). Reports ms per frame with the build (bins / Embree BVH / grids)
// and the trace separated, Mrays/s and chords per ray. Medians over repetitions:
//   build/bench/bench_volume --benchmark_filter='mode:0' --benchmark_repetitions=3
// The screen bins keep their entry array for the next call (as for the next frame of a render), so
// a process's first repetition also pays for faulting in fresh pages (at 15M about 290 MB); it is
// printed first, before the aggregates.
#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <cmath>
#include <map>
#include <memory>

#include "sim/core/parallel.h"
#include "sim/core/rng.h"
#include "render/volume/volume_pass.h"

namespace spume {
namespace {

struct Box {
  DiffuseFrame frame;
  float radius;
};

const Box& box(size_t n) {
  static std::map<size_t, std::unique_ptr<Box>> cache;  // 15M takes a moment to generate
  auto& slot = cache[n];
  if (!slot) {
    slot = std::make_unique<Box>();
    slot->radius = 0.35f * std::cbrt(1.0f / float(n));
    slot->frame.positions.resize(n);
    slot->frame.types.assign(n, DiffuseType::Foam);
    parallel_for(n, 1 << 16, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) {
        const auto u = random_uniform4({12345, RandomPurpose::Test, 0, i, 0});
        slot->frame.positions[i] = Vec3f(u[0], u[1], u[2]);
      }
    });
  }
  return *slot;
}

Camera box_camera() {
  Camera c;
  c.position = Vec3f(0.5f, 0.5f, 1.7f);
  c.target = Vec3f(0.5f, 0.5f, 0.5f);
  c.fov_y_degrees = 45.0f;
  c.width = 1920, c.height = 1080;
  return c;
}

// User + system CPU time of the whole process (all threads), s: with other jobs sharing the two
// cores, wall time alone says little; cpu / 2 is what an idle 2-core machine would take at best.
double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;
}

// Arguments: N, mode (0 exact/screen bins, 1 exact/Embree all hits, 2 march with dx = r).
void BM_VolumeBox(benchmark::State& state) {
  const Box& b = box(size_t(state.range(0)));
  VolumeSettings s;
  s.look[size_t(DiffuseType::Foam)] = {b.radius, Vec3f(0.9f, 0.95f, 1.0f)};
  s.alpha = 1.0f / (20.0f * b.radius);  // optical depth ~1 over a typical path
  const int mode = int(state.range(1));
  s.integrator = mode == 2 ? VolumeIntegrator::March : VolumeIntegrator::Exact;
  s.exact_method = mode == 1 ? ExactMethod::EmbreeAllHits : ExactMethod::ScreenBins;
  s.march_step = b.radius;
  const Camera cam = box_camera();
  VolumeStats st;
  double build = 0, trace = 0;
  const double cpu0 = process_cpu_seconds();
  for (auto _ : state) {
    VolumeImage img = render_volume(b.frame, cam, s, {}, &st);
    benchmark::DoNotOptimize(img.transmittance.data());
    build += st.build_seconds, trace += st.trace_seconds;
  }
  const double it = double(state.iterations());
  state.counters["cpu_ms"] = 1e3 * (process_cpu_seconds() - cpu0) / it;
  state.counters["build_ms"] = 1e3 * build / it;
  state.counters["trace_ms"] = 1e3 * trace / it;
  state.counters["Mrays_per_s"] = double(st.rays) * it / (build + trace) / 1e6;
  state.counters[mode == 2 ? "samples_per_ray" : "chords_per_ray"] = double(st.intervals) / double(st.rays);
  state.counters["peak_rss_MB"] = peak_rss_mb();
  state.counters["threads"] = thread_count();
  state.SetLabel(mode == 0 ? "exact/screen-bins" : mode == 1 ? "exact/embree-all-hits" : "march dx=r");
}

BENCHMARK(BM_VolumeBox)
    ->ArgsProduct({{1000000, 15000000}, {0, 1, 2}})
    ->ArgNames({"N", "mode"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace spume

BENCHMARK_MAIN();

// Diffuse simulator throughput on a fixed synthetic frame: 640k fluid particles in a wavy pool; 1M,
// 3M, 15M or 100M (about 13 GiB) diffuse particles placed like a real frame's: a third inside the
// fluid, a third within h of its surface, a third in the air above. One frame step (classify, potentials, emission,
// advection), split by stage, with the working buffers of a running simulation, and the frame's
// diffuse cache written as the pipeline writes it (quantized .spd, to a file in the temporary
// directory; the page cache absorbs it, so this is the encode and the copy into the kernel, not the
// disk; SPUME_BENCH_CACHE=path writes it there instead and keeps it, e.g. for bench_cache). Run:
//   build/bench/bench_diffuse --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sys/resource.h>

#include "sim/core/parallel.h"
#include "sim/core/stopwatch.h"
#include "sim/diffuse/simulator.h"
#include "sim/io/diffuse_quantized.h"
#include "sim/io/spume_cache.h"
#include "sim/scene/diffuse_params_reader.h"

namespace spume {
namespace {

constexpr float kRadius = 0.01f, kSpacing = 2 * kRadius, kH = 4 * kRadius;
constexpr int kNx = 200, kNy = 16, kNz = 200;  // 640,000 particles
constexpr float kDepth = kNy * kSpacing;

float surface_height(float x, float z, float t) { return kDepth + 0.03f * std::sin(6.0f * x + 3.0f * t) * std::cos(4.0f * z); }

// Fluid frame at time t: a lattice pool whose top follows a travelling wave, moving with it.
FluidFrame pool_frame(int index, double t) {
  FluidFrame f;
  f.index = index, f.time = t;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> jitter(-0.1f * kSpacing, 0.1f * kSpacing);
  uint32_t id = 0;
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i, ++id) {
        const float x = i * kSpacing, z = k * kSpacing;
        const float stretch = surface_height(x, z, float(t)) / kDepth;
        const float y = (j + 0.5f) * kSpacing * stretch;
        f.positions.emplace_back(x + jitter(rng), y + jitter(rng), z + jitter(rng));
        const float wave = 0.6f * std::cos(6.0f * x + 3.0f * float(t));
        f.velocities.emplace_back(wave, 0.5f * wave * (y / kDepth), 0.2f * wave);
        f.ids.push_back(id);
      }
  return f;
}

DiffuseFrame diffuse_like_a_real_frame(size_t n) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  DiffuseFrame d;
  d.resize(n);
  const float wx = kNx * kSpacing, wz = kNz * kSpacing;
  for (size_t i = 0; i < n; ++i) {
    const float x = u(rng) * wx, z = u(rng) * wz, top = surface_height(x, z, 0.0f);
    float y;
    DiffuseType type;
    switch (i % 3) {
      case 0: y = u(rng) * (top - kH), type = DiffuseType::Bubble; break;        // inside
      case 1: y = top + (2 * u(rng) - 1) * kH, type = DiffuseType::Foam; break;   // at the surface
      default: y = top + kH + u(rng) * 0.5f, type = DiffuseType::Spray; break;    // in the air
    }
    d.positions[i] = Vec3f(x, y, z);
    d.velocities[i] = Vec3f(0.1f, 0.5f, 0.0f);
    d.lifetimes[i] = 2.0f;
    d.types[i] = type;
    d.ids[i] = diffuse_id(uint32_t(i / 16), 0, uint32_t(i % 16));
  }
  return d;
}

void BM_DiffuseFrame(benchmark::State& state) {
  static const FluidFrame a = pool_frame(10, 10 / 50.0), b = pool_frame(11, 11 / 50.0);
  const size_t n = size_t(state.range(0));
  DiffuseSetup setup;
  setup.fluid.particle_radius = kRadius, setup.fluid.support_radius = kH, setup.fluid.fps = 50;
  setup.params = read_diffuse_params(ParamReader::from_json(Json::object(), "bench"), setup.fluid, Vec3f(0, -9.81f, 0));
  setup.domain.min = Vec3f(-1, -1, -1), setup.domain.max = Vec3f(6, 3, 6);
  std::array<double, size_t(Stage::Count)> stage_ms{};
  double generated = 0, cache_ms = 0;
  const char* keep = std::getenv("SPUME_BENCH_CACHE");
  const std::filesystem::path cache =
      keep ? std::filesystem::path(keep) : std::filesystem::temp_directory_path() / "spume_bench_diffuse.spd";
  auto write = [&](const DiffuseFrame& frame, const FrameStats&) {
    write_diffuse_cache(cache, frame, kRadius / kPositionStepsPerRadius);
  };
  // As the pipeline writes a frame's cache, from the callback that hands the classified frame over.
  auto write_cache = [&](const DiffuseFrame& frame, const FrameStats& stats) {
    const Stopwatch watch;
    write(frame, stats);
    cache_ms += watch.milliseconds();
  };
  // A running simulation keeps its particles in cell order and its working buffers (the cache
  // writer's too) from frame to frame: before each timed frame, one untimed frame from freshly placed
  // particles puts them in order (rebuilt rather than copied, so that peak memory is the simulator's own).
  DiffuseSimulator sim(setup);
  auto place_and_warm_up = [&] {
    sim.set_particles(DiffuseFrame{});  // free the previous particles first
    sim.set_particles(diffuse_like_a_real_frame(n));
    sim.process_frame(a, &b, write);
    sim.process_frame(b, nullptr, [](const DiffuseFrame&, const FrameStats&) {});
  };
  for (auto _ : state) {
    state.PauseTiming();
    place_and_warm_up();
    state.ResumeTiming();
    // One frame of work: the grid, classification against frame 10 and its cache, then the step to frame 11.
    const FrameStats first = sim.process_frame(a, &b, write_cache);
    state.PauseTiming();
    // The step's stages are reported with the next frame; its own classification is not timed here.
    const FrameStats second = sim.process_frame(b, nullptr, [](const DiffuseFrame&, const FrameStats&) {});
    state.ResumeTiming();
    for (Stage s : {Stage::Grid, Stage::Classify}) stage_ms[size_t(s)] += first.stage_ms[size_t(s)];
    for (Stage s : {Stage::Potentials, Stage::Emit, Stage::Advect}) stage_ms[size_t(s)] += second.stage_ms[size_t(s)];
    generated += double(second.generated);
  }
  const double iterations = double(state.iterations());
  for (size_t s = 0; s < stage_ms.size(); ++s) state.counters[std::string(kStageNames[s]) + "_ms"] = stage_ms[s] / iterations;
  state.counters["cache_ms"] = cache_ms / iterations;
  state.counters["cache_bytes_per_particle"] = double(std::filesystem::file_size(cache)) / double(n);
  if (!keep) std::filesystem::remove(cache);
  state.counters["generated"] = generated / iterations;
  state.counters["updates_per_s_per_core"] =
      benchmark::Counter(double(n) / thread_count(), benchmark::Counter::kIsIterationInvariantRate);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = double(usage.ru_maxrss) / 1024.0;
}

BENCHMARK(BM_DiffuseFrame)->Arg(1'000'000)->Arg(3'000'000)->Arg(15'000'000)->Arg(100'000'000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace
}  // namespace spume

BENCHMARK_MAIN();

// Diffuse cache write and read on a real frame: the raw version 1 layout (37 bytes a particle, as
// spume wrote it before the compact caches) against version 2, quantized as the pipeline writes it
// and exact (the restart state). Bytes a particle are reported as counters. Run:
//   SPUME_BENCH_SPD=out/wave/diffuse/diffuse_0100.spd SPUME_BENCH_RADIUS=0.02
//   build/bench/bench_cache --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// SPUME_BENCH_SPD names any diffuse cache (either version); SPUME_BENCH_RADIUS is the fluid particle
// radius it was simulated with (the position step is radius / kPositionStepsPerRadius).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "sim/io/crc_file.h"
#include "sim/io/io_bytes.h"
#include "sim/io/spume_cache.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

const DiffuseFrame& frame() {
  static const DiffuseFrame f = [] {
    const char* path = std::getenv("SPUME_BENCH_SPD");
    if (!path) {
      std::cerr << "set SPUME_BENCH_SPD to a diffuse cache (.spd) and SPUME_BENCH_RADIUS to its fluid radius\n";
      std::exit(2);
    }
    return read_diffuse_cache(path);
  }();
  return f;
}

double position_step() {
  const char* r = std::getenv("SPUME_BENCH_RADIUS");
  return (r ? std::atof(r) : 0.02) / kPositionStepsPerRadius;
}

fs::path scratch(const char* name) { return fs::temp_directory_path() / (std::string("spume_bench_") + name); }

// Version 1 exactly as spume wrote it: validation, header, the five arrays, CRC.
void write_raw(const fs::path& path, const DiffuseFrame& f) {
  f.validate(path.string());
  std::string header("SPUMEDF1", 8);
  io::store(header, kRawDiffuseCacheVersion, io::Endian::Little);
  io::store(header, int32_t(f.index), io::Endian::Little);
  io::store(header, f.time, io::Endian::Little);
  io::store(header, uint64_t(f.size()), io::Endian::Little);
  for (size_t c : f.count_by_type()) io::store(header, uint64_t(c), io::Endian::Little);
  write_crc_file(path, header, f.ids, f.positions, f.velocities, f.lifetimes, f.types);
}

void report(benchmark::State& state, const fs::path& path) {
  state.counters["particles"] = double(frame().size());
  state.counters["bytes_per_particle"] = double(fs::file_size(path)) / double(std::max<size_t>(1, frame().size()));
}

void BM_WriteRaw(benchmark::State& state) {
  const fs::path p = scratch("raw.spd");
  for (auto _ : state) write_raw(p, frame());
  report(state, p);
}

void BM_WriteQuantized(benchmark::State& state) {
  const fs::path p = scratch("quantized.spd");
  for (auto _ : state) write_diffuse_cache(p, frame(), position_step());
  report(state, p);
}

void BM_WriteExact(benchmark::State& state) {
  const fs::path p = scratch("exact.spd");
  for (auto _ : state) write_diffuse_cache(p, frame());
  report(state, p);
}

template <int kind>
void BM_Read(benchmark::State& state) {
  const fs::path p = scratch(kind == 0 ? "raw.spd" : kind == 1 ? "quantized.spd" : "exact.spd");
  if (kind == 0) write_raw(p, frame());
  if (kind == 1) write_diffuse_cache(p, frame(), position_step());
  if (kind == 2) write_diffuse_cache(p, frame());
  for (auto _ : state) benchmark::DoNotOptimize(read_diffuse_cache(p));
  report(state, p);
}

BENCHMARK(BM_WriteRaw)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_WriteQuantized)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_WriteExact)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_TEMPLATE(BM_Read, 0)->Name("BM_ReadRaw")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_TEMPLATE(BM_Read, 1)->Name("BM_ReadQuantized")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_TEMPLATE(BM_Read, 2)->Name("BM_ReadExact")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace
}  // namespace spume

BENCHMARK_MAIN();

// The compact diffuse cache's quantization (sim/io/diffuse_quantized.h): every particle comes back, its
// id and type exact, position, velocity and lifetime within the stated bounds, which the tests compute
// from the frame themselves: position step / 2 per axis, the frame's largest |velocity component| /
// 65534, (longest - shortest lifetime) / 131070, each plus the rounding of the result to float.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "sim/core/parallel.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"
#include "sim/io/spume_cache.h"

namespace fs = std::filesystem;
using namespace spume;
using namespace spume::testing;

namespace {

constexpr double kStep = 0.01 / 64;  // r = 1 cm, as the pipeline quantizes

float half_ulp(float x) { return 0.5f * (std::nextafter(std::abs(x), std::numeric_limits<float>::infinity()) - std::abs(x)); }

// Writes d quantized with kStep, reads it back and checks every particle against the bounds.
DiffuseFrame round_trip(const DiffuseFrame& d, double step = kStep) {
  TempDir dir;
  const fs::path p = dir.path / "q.spd";
  write_diffuse_cache(p, d, step);
  DiffuseCacheHeader h;
  const DiffuseFrame e = read_diffuse_cache(p, &h);
  EXPECT_EQ(e.size(), d.size());
  EXPECT_EQ(e.index, d.index);
  EXPECT_EQ(e.time, d.time);
  // The renderer's read (positions and types only) gives the same particles in the same order, so the
  // bounds checked below hold for it too.
  DiffuseCacheHeader points_header;
  const DiffusePoints points = read_diffuse_points(p, &points_header);
  EXPECT_EQ(points.index, d.index);
  EXPECT_EQ(points.time, d.time);
  EXPECT_TRUE(points.positions == e.positions);
  EXPECT_TRUE(points.types == e.types);
  EXPECT_EQ(points_header.count_by_type, h.count_by_type);
  double vmax = 0.0, lmin = INFINITY, lmax = -INFINITY;
  for (size_t i = 0; i < d.size(); ++i) {
    for (int a = 0; a < 3; ++a) vmax = std::max(vmax, std::abs(double(d.velocities[i][a])));
    lmin = std::min(lmin, double(d.lifetimes[i]));
    lmax = std::max(lmax, double(d.lifetimes[i]));
  }
  std::map<uint64_t, size_t> by_id;
  for (size_t k = 0; k < e.size(); ++k) by_id[e.ids[k]] = k;
  EXPECT_EQ(by_id.size(), d.size());
  int failures = 0;
  for (size_t i = 0; i < d.size() && failures < 5; ++i) {
    const auto found = by_id.find(d.ids[i]);
    if (found == by_id.end()) {
      ADD_FAILURE() << "particle " << i << " (id " << d.ids[i] << ") is missing", ++failures;
      continue;
    }
    const size_t k = found->second;
    bool ok = e.types[k] == d.types[i];
    for (int a = 0; a < 3; ++a) {
      ok &= std::abs(double(e.positions[k][a]) - double(d.positions[i][a])) <= step / 2 * (1 + 1e-9) + half_ulp(e.positions[k][a]);
      ok &= std::abs(double(e.velocities[k][a]) - double(d.velocities[i][a])) <=
            vmax / 65534 * (1 + 1e-9) + half_ulp(e.velocities[k][a]);
    }
    ok &= std::abs(double(e.lifetimes[k]) - double(d.lifetimes[i])) <= (lmax - lmin) / 131070 * (1 + 1e-9) + half_ulp(e.lifetimes[k]);
    if (!ok) {
      ++failures;
      ADD_FAILURE() << "particle " << i << ": position " << d.positions[i].transpose() << " -> " << e.positions[k].transpose()
                    << ", velocity " << d.velocities[i].transpose() << " -> " << e.velocities[k].transpose() << ", life "
                    << d.lifetimes[i] << " -> " << e.lifetimes[k] << ", type " << int(d.types[i]) << " -> " << int(e.types[k]);
    }
  }
  return e;
}

DiffuseFrame random_frame(size_t n, uint32_t seed, float extent = 3.0f, float speed = 5.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  DiffuseFrame d;
  d.index = 12, d.time = 0.5;
  d.resize(n);
  for (size_t i = 0; i < n; ++i) {
    d.ids[i] = diffuse_id(uint32_t(rng() % 300000), uint32_t(rng() % 4000), uint32_t(i % 4096)) ^ (uint64_t(i) << 44);
    d.positions[i] = Vec3f(u(rng) * extent - 1.0f, u(rng) * extent * 0.3f, u(rng) * extent * 0.5f + 2.0f);
    d.velocities[i] = Vec3f(speed * (2 * u(rng) - 1), speed * (2 * u(rng) - 1), speed * (2 * u(rng) - 1));
    d.lifetimes[i] = 3.0f * u(rng);
    d.types[i] = DiffuseType(rng() % 3);
  }
  return d;
}

TEST(DiffuseQuantized, RandomParticlesComeBackWithinTheStatedErrors) {
  const DiffuseFrame d = random_frame(50'000, 1);
  round_trip(d);
  // The bounds are tight: a quarter of the stated position error is exceeded somewhere.
  const DiffuseFrame e = round_trip(d);
  std::map<uint64_t, size_t> at;
  for (size_t i = 0; i < d.size(); ++i) at[d.ids[i]] = i;
  double worst = 0.0;
  for (size_t k = 0; k < e.size(); ++k)
    worst = std::max(worst, double((e.positions[k] - d.positions[at[e.ids[k]]]).cwiseAbs().maxCoeff()));
  EXPECT_GT(worst, kStep / 4);
  EXPECT_LE(worst, kStep / 2 + 1e-6);
}

TEST(DiffuseQuantized, RandomValuesTakeNoMoreThanTheirQuantizedBits) {
  // 200k particles in a 0.6 m box with r = 1 cm, velocities, lifetimes and ids uniformly random (the
  // codec's worst case; real frames are measured by bench/bench_cache): 3 offset bytes, 6 velocity,
  // 2 lifetime, 8 id and a quarter byte of type a particle, 19.25 bytes, against the raw 37.
  TempDir dir;
  DiffuseFrame d = random_frame(200'000, 2, 0.6f, 2.0f);
  write_diffuse_cache(dir.path / "q.spd", d, kStep);
  EXPECT_LT(fs::file_size(dir.path / "q.spd"), 19.25 * double(d.size()));
}

TEST(DiffuseQuantized, AdversarialFrames) {
  DiffuseFrame d = random_frame(1000, 3);
  // The bounds' extremes, particles on both corners and on the faces.
  d.positions[0] = Vec3f(-1.0f, 0.0f, 2.0f);
  d.positions[1] = Vec3f(2.0f, 0.9f, 3.5f);
  d.positions[2] = Vec3f(-1.0f, 0.9f, 2.0f);
  round_trip(d);
  // Huge velocities beside small ones: the small ones are within vmax / 65534 of theirs.
  d.velocities[3] = Vec3f(3e38f, -3e38f, 1e30f);
  d.velocities[4] = Vec3f(-1e-30f, 0.0f, 1e-3f);
  round_trip(d);
  // Zero-size bounds: every particle at one point, at rest, one lifetime: all exact.
  DiffuseFrame same = random_frame(100, 4);
  for (size_t i = 0; i < same.size(); ++i) {
    same.positions[i] = Vec3f(0.1f, 0.2f, 0.3f);
    same.velocities[i] = Vec3f(0, 0, 0);
    same.lifetimes[i] = 1.5f;
  }
  const DiffuseFrame e = round_trip(same);
  for (size_t k = 0; k < e.size(); ++k) {
    EXPECT_EQ(e.positions[k], Vec3f(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(e.velocities[k], Vec3f(0, 0, 0));
    EXPECT_EQ(e.lifetimes[k], 1.5f);
  }
  // Negative lifetimes (the format does not assume life >= 0).
  d.lifetimes[5] = -2.0f;
  round_trip(d);
  // One particle; no particles.
  round_trip(random_frame(1, 5));
  EXPECT_EQ(round_trip(random_frame(0, 6)).size(), 0u);
}

TEST(DiffuseQuantized, NonFiniteValuesAreRefusedOnWrite) {
  TempDir dir;
  for (int field = 0; field < 3; ++field) {
    DiffuseFrame d = random_frame(10, 7);
    if (field == 0) d.positions[4].y() = std::numeric_limits<float>::quiet_NaN();
    if (field == 1) d.velocities[4].x() = std::numeric_limits<float>::infinity();
    if (field == 2) d.lifetimes[4] = std::numeric_limits<float>::quiet_NaN();
    const fs::path p = dir.path / "nan.spd";
    const std::string msg = error_of([&] { write_diffuse_cache(p, d, kStep); });
    EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("particle 4"), std::string::npos) << msg;
    EXPECT_NE(msg.find("non-finite"), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(p));
  }
  const std::string msg = error_of([&] { write_diffuse_cache(dir.path / "s.spd", random_frame(3, 8), -1.0); });
  EXPECT_NE(msg.find("position step -1"), std::string::npos) << msg;
}

TEST(DiffuseQuantized, TheFirstBadParticleIsNamedWhateverTheThreads) {
  // Bad particles far apart in the frame, which the check splits among threads in runs of at least
  // 65,536: the message names the first, a non-finite value before a bad type.
  DiffuseFrame d = random_frame(300'000, 10);
  d.lifetimes[250'000] = std::numeric_limits<float>::quiet_NaN();
  d.types[140'001] = DiffuseType(7);
  d.positions[140'000].x() = std::numeric_limits<float>::infinity();
  const std::string msg = error_of([&] { d.validate("frame"); });
  EXPECT_NE(msg.find("particle 140000 "), std::string::npos) << msg;
  EXPECT_NE(msg.find("non-finite"), std::string::npos) << msg;
  d.positions[140'000].x() = 0.0f;
  const std::string type_msg = error_of([&] { d.validate("frame"); });
  EXPECT_NE(type_msg.find("particle 140001 has type 7"), std::string::npos) << type_msg;
  d.velocities[100'003].z() = -std::numeric_limits<float>::infinity();
  const std::string velocity_msg = error_of([&] { d.validate("frame"); });
  EXPECT_NE(velocity_msg.find("particle 100003 "), std::string::npos) << velocity_msg;
}

TEST(DiffuseQuantized, AFrameTooWideForTheGridIsStoredExactly) {
  // 2^31 steps of r / 64 at r = 1 cm is 335 km: a particle beyond that cannot be quantized in 32 bits.
  TempDir dir;
  DiffuseFrame d = random_frame(100, 9);
  d.positions[7] = Vec3f(4e5f, 0.0f, 0.0f);
  const fs::path p = dir.path / "wide.spd";
  write_diffuse_cache(p, d, kStep);
  DiffuseCacheHeader h;
  const DiffuseFrame e = read_diffuse_cache(p, &h);
  EXPECT_FALSE(h.quantized);
  EXPECT_EQ(e.positions, d.positions);
  EXPECT_EQ(e.ids, d.ids);
}

TEST(DiffuseQuantized, TheSameBytesForAnyThreadCount) {
  // 300k particles: 2.4 MB of ids, so the columns span several chunks compressed in parallel.
  TempDir dir;
  const DiffuseFrame d = random_frame(300'000, 10);
  std::string bytes[2];
  for (int threads : {1, 2}) {
    set_thread_count(threads);
    write_diffuse_cache(dir.path / "t.spd", d, kStep);
    bytes[threads - 1] = read_file(dir.path / "t.spd");
  }
  set_thread_count(0);
  EXPECT_TRUE(bytes[0] == bytes[1]);
  EXPECT_GT(bytes[0].size(), size_t(1) << 20);
}

TEST(DiffuseQuantized, HeaderStatesTheQuantization) {
  TempDir dir;
  DiffuseFrame d = random_frame(100, 11);
  d.velocities[0] = Vec3f(0, -32.767f, 0);  // the largest component: step 1 mm/s
  for (auto& v : d.velocities) v = v.cwiseMax(Vec3f::Constant(-32.767f)).cwiseMin(Vec3f::Constant(32.767f));
  write_diffuse_cache(dir.path / "h.spd", d, kStep);
  const DiffuseCacheHeader h = peek_diffuse_cache(dir.path / "h.spd");
  EXPECT_TRUE(h.quantized);
  EXPECT_EQ(h.quantization.position_step, kStep);
  EXPECT_NEAR(h.quantization.velocity_step, 0.001, 1e-9);
  float lo = INFINITY;
  for (const Vec3f& p : d.positions) lo = std::min(lo, p.x());
  EXPECT_EQ(h.quantization.origin[0], double(lo));
}

}  // namespace

TEST(DiffuseQuantized, ParticlesAreStoredByCellAndKeepTheirOrderWithinACell) {
  // 300k particles in 0.6 x 0.18 x 0.3 m: about 4k cells of 128 steps (2 cm) a side, some 70 particles
  // each, so the sort runs several passes over several chunks. The stored order is recomputed here
  // from the format's definition: cells x-fastest from the frame's lower bounds, and within a cell
  // the frame's order.
  TempDir dir;
  const DiffuseFrame d = random_frame(300'000, 12, 0.6f);
  const fs::path p = dir.path / "o.spd";
  write_diffuse_cache(p, d, kStep);
  const DiffuseFrame e = read_diffuse_cache(p);
  ASSERT_EQ(e.size(), d.size());
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = INFINITY, hi[a] = -INFINITY;
  for (const Vec3f& x : d.positions)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], double(x[a])), hi[a] = std::max(hi[a], double(x[a]));
  auto cell = [&](const Vec3f& x, int a) { return uint64_t(std::llround((double(x[a]) - lo[a]) / kStep)) / 128; };
  const uint64_t nx = cell(Vec3f(float(hi[0]), float(hi[1]), float(hi[2])), 0) + 1;
  const uint64_t ny = cell(Vec3f(float(hi[0]), float(hi[1]), float(hi[2])), 1) + 1;
  std::map<uint64_t, size_t> index_of;
  for (size_t i = 0; i < d.size(); ++i) index_of[d.ids[i]] = i;
  uint64_t previous_key = 0;
  size_t previous_index = 0, cells = 0, out_of_order = 0;
  for (size_t k = 0; k < e.size(); ++k) {
    const size_t i = index_of.at(e.ids[k]);
    const Vec3f& x = d.positions[i];
    const uint64_t key = cell(x, 0) + nx * (cell(x, 1) + ny * cell(x, 2));
    if (k > 0 && (key < previous_key || (key == previous_key && i < previous_index))) ++out_of_order;
    cells += k == 0 || key != previous_key;
    previous_key = key, previous_index = i;
  }
  EXPECT_EQ(out_of_order, 0u);
  EXPECT_GT(cells, 3000u);
  EXPECT_LT(cells, 6000u);
}

TEST(DiffuseQuantized, AFrameOfMoreThan2To32CellsIsStillQuantized) {
  // 300 km along x and y: 1.9e9 steps of r / 64 (under 2^31) but 2.2e14 cells of 128 steps, more than
  // a 32-bit cell key holds; those frames sort by 64-bit keys.
  TempDir dir;
  DiffuseFrame d = random_frame(5000, 13);
  d.positions[17] = Vec3f(3e5f, 3e5f, 2.0f);
  const DiffuseFrame e = round_trip(d);
  EXPECT_EQ(e.size(), d.size());
  write_diffuse_cache(dir.path / "w.spd", d, kStep);
  EXPECT_TRUE(peek_diffuse_cache(dir.path / "w.spd").quantized);
}

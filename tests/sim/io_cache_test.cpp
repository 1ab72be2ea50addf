#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <vector>

#include "sim/core/error.h"
#include "tests/support/crc_trailer.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"
#include "sim/io/column_codec.h"
#include "sim/io/crc_file.h"
#include "sim/io/spume_cache.h"

namespace fs = std::filesystem;
using namespace spume;
using namespace spume::testing;

namespace {

template <typename T>
T at(const std::string& bytes, size_t offset) {  // little-endian host, like the format
  T v;
  std::memcpy(&v, bytes.data() + offset, sizeof(T));
  return v;
}

template <typename T>
void put(std::string& bytes, size_t offset, T v) {
  std::memcpy(bytes.data() + offset, &v, sizeof(T));
}

FluidFrame sample_fluid() {
  FluidFrame f;
  f.index = 17;
  f.time = 0.34;
  f.positions = {Vec3f(0, 0, 0), Vec3f(1, 2, 3), Vec3f(-0.5f, 0.25f, 1e-6f)};
  f.velocities = {Vec3f(0, -1, 0), Vec3f(2, 0, 0), Vec3f(0, 0, 3)};
  f.ids = {5, 9, 4000000000u};
  f.masses = {0.1f, 0.2f, 0.3f};
  return f;
}

DiffuseFrame sample_diffuse() {
  DiffuseFrame d;
  d.index = 3;
  d.time = 0.06;
  d.ids = {diffuse_id(1, 2, 3), diffuse_id(7, 8, 9), diffuse_id(4000000000u, kMaxBirthStep, 1), diffuse_id(0, 0, 0)};
  d.positions = {Vec3f(0, 1, 0), Vec3f(1, 1, 1), Vec3f(2, 0, 0), Vec3f(-3, 0, 1)};
  d.velocities = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 2, 0), Vec3f(0, 0, -3)};
  d.lifetimes = {0.5f, 1.0f, 2.5f, 0.0f};
  d.types = {DiffuseType::Spray, DiffuseType::Foam, DiffuseType::Bubble, DiffuseType::Spray};
  return d;
}

// A version 1 (raw) diffuse cache built byte by byte from the documented layout, as spume wrote them
// before the compact caches.
std::string raw_diffuse_bytes(const DiffuseFrame& d) {
  std::string b = "SPUMEDF1";
  auto add = [&](const auto& v) { b.append(reinterpret_cast<const char*>(&v), sizeof v); };
  add(uint32_t(1)), add(int32_t(d.index)), add(d.time), add(uint64_t(d.size()));
  for (int t = 0; t < 3; ++t) add(uint64_t(std::count(d.types.begin(), d.types.end(), DiffuseType(t))));
  for (uint64_t id : d.ids) add(id);
  for (const Vec3f& p : d.positions) add(p.x()), add(p.y()), add(p.z());
  for (const Vec3f& v : d.velocities) add(v.x()), add(v.y()), add(v.z());
  for (float l : d.lifetimes) add(l);
  for (DiffuseType t : d.types) add(uint8_t(t));
  b += "CRC!";
  return with_fixed_crc(b);
}

}  // namespace

TEST(Cache, FluidRoundTripMatchesTheDocumentedLayout) {
  TempDir dir;
  const FluidFrame f = sample_fluid();
  const fs::path p = dir.path / "f.spf";
  write_fluid_cache(p, f, 0.025f);
  const std::string b = read_file(p);
  // 40-byte header + 3 * (4 id + 12 position + 12 velocity + 4 mass) + 4 CRC.
  ASSERT_EQ(b.size(), 40u + 3 * 32 + 4);
  EXPECT_EQ(b.substr(0, 8), "SPUMEFL1");
  EXPECT_EQ(at<uint32_t>(b, 8), 1u);
  EXPECT_EQ(at<int32_t>(b, 12), 17);
  EXPECT_EQ(at<double>(b, 16), 0.34);
  EXPECT_EQ(at<float>(b, 24), 0.025f);
  EXPECT_EQ(at<uint64_t>(b, 28), 3u);
  EXPECT_EQ(at<uint32_t>(b, 36), 7u);
  EXPECT_EQ(at<uint32_t>(b, 40 + 8), 4000000000u);  // third id
  EXPECT_EQ(at<float>(b, 40 + 12 + 12 + 4), 2.0f);   // second position's y
  EXPECT_EQ(at<float>(b, 40 + 12 + 36 + 12), 2.0f);  // second velocity's x
  EXPECT_EQ(at<float>(b, 40 + 12 + 36 + 36 + 8), 0.3f);
  EXPECT_EQ(at<uint32_t>(b, b.size() - 4), uint32_t(crc32(0, reinterpret_cast<const Bytef*>(b.data()), uInt(b.size() - 4))));

  FluidCacheHeader h;
  const FluidFrame g = read_fluid_cache(p, &h);
  EXPECT_EQ(g.index, 17);
  EXPECT_EQ(g.time, 0.34);
  EXPECT_EQ(h.particle_radius, 0.025f);
  EXPECT_EQ(g.positions, f.positions);
  EXPECT_EQ(g.velocities, f.velocities);
  EXPECT_EQ(g.ids, f.ids);
  EXPECT_EQ(g.masses, f.masses);
  EXPECT_EQ(peek_fluid_cache(p).count, 3u);
}

TEST(Cache, FluidWithoutOptionalArraysAndEmpty) {
  TempDir dir;
  FluidFrame f;
  f.positions = {Vec3f(1, 2, 3), Vec3f(4, 5, 6)};
  const fs::path p = dir.path / "bare.spf";
  write_fluid_cache(p, f, 0.01f);
  EXPECT_EQ(fs::file_size(p), 40u + 2 * 12 + 4);
  const FluidFrame g = read_fluid_cache(p);
  EXPECT_EQ(g.positions, f.positions);
  EXPECT_FALSE(g.has_velocities());
  EXPECT_FALSE(g.has_ids());
  write_fluid_cache(p, FluidFrame{}, 0.01f);
  EXPECT_EQ(read_fluid_cache(p).size(), 0u);
}

TEST(Cache, DiffuseRoundTripMatchesTheDocumentedLayout) {
  TempDir dir;
  const DiffuseFrame d = sample_diffuse();
  const fs::path p = dir.path / "sub" / "d.spd";
  write_diffuse_cache(p, d);  // exact
  const std::string b = read_file(p);
  ASSERT_GT(b.size(), 136u + 4);
  EXPECT_EQ(b.substr(0, 8), "SPUMEDF1");
  EXPECT_EQ(at<uint32_t>(b, 8), 2u);
  EXPECT_EQ(at<int32_t>(b, 12), 3);
  EXPECT_EQ(at<double>(b, 16), 0.06);
  EXPECT_EQ(at<uint64_t>(b, 24), 4u);
  EXPECT_EQ(at<uint64_t>(b, 32), 2u);  // spray
  EXPECT_EQ(at<uint64_t>(b, 40), 1u);  // foam
  EXPECT_EQ(at<uint64_t>(b, 48), 1u);  // bubble
  EXPECT_EQ(at<uint32_t>(b, 56), 0u);  // exact
  EXPECT_EQ(at<uint64_t>(b, 120), 0u);  // no cells
  EXPECT_EQ(at<uint64_t>(b, 136), 4u * 8);  // the first column, the ids, holds 8 bytes a particle
  EXPECT_EQ(at<uint32_t>(b, b.size() - 4), uint32_t(crc32(0, reinterpret_cast<const Bytef*>(b.data()), uInt(b.size() - 4))));
  DiffuseCacheHeader h;
  const DiffuseFrame e = read_diffuse_cache(p, &h);
  EXPECT_EQ(e.index, 3);
  EXPECT_EQ(e.time, 0.06);
  EXPECT_EQ(e.ids, d.ids);
  EXPECT_EQ(e.positions, d.positions);
  EXPECT_EQ(e.velocities, d.velocities);
  EXPECT_EQ(e.lifetimes, d.lifetimes);
  EXPECT_EQ(e.types, d.types);
  EXPECT_FALSE(h.quantized);
  EXPECT_EQ(h.count_by_type, (std::array<uint64_t, 3>{2, 1, 1}));
  EXPECT_EQ(peek_diffuse_cache(p).count_by_type, h.count_by_type);
  const DiffusePoints points = read_diffuse_points(p);  // an exact cache: the frame's own order and bits
  EXPECT_EQ(points.index, 3);
  EXPECT_EQ(points.time, 0.06);
  EXPECT_EQ(points.positions, d.positions);
  EXPECT_EQ(points.types, d.types);
}

TEST(Cache, VersionOneDiffuseCachesAreStillRead) {
  TempDir dir;
  const DiffuseFrame d = sample_diffuse();
  const fs::path p = dir.write("old.spd", raw_diffuse_bytes(d));
  DiffuseCacheHeader h;
  const DiffuseFrame e = read_diffuse_cache(p, &h);
  EXPECT_EQ(h.version, 1u);
  EXPECT_EQ(e.index, 3);
  EXPECT_EQ(e.ids, d.ids);
  EXPECT_EQ(e.positions, d.positions);
  EXPECT_EQ(e.velocities, d.velocities);
  EXPECT_EQ(e.lifetimes, d.lifetimes);
  EXPECT_EQ(e.types, d.types);
  EXPECT_EQ(peek_diffuse_cache(p).count, 4u);
  const DiffusePoints points = read_diffuse_points(p);
  EXPECT_EQ(points.index, 3);
  EXPECT_EQ(points.positions, d.positions);
  EXPECT_EQ(points.types, d.types);
}

TEST(Cache, AnUnknownDiffuseVersionIsRefusedNamingTheFileAndWhatToDo) {
  TempDir dir;
  const fs::path good = dir.path / "good.spd";
  write_diffuse_cache(good, sample_diffuse());
  std::string b = read_file(good);
  put<uint32_t>(b, 8, 3);
  const fs::path p = dir.write("v3.spd", with_fixed_crc(b));
  for (const std::string& msg : {error_of([&] { read_diffuse_cache(p); }), error_of([&] { peek_diffuse_cache(p); })}) {
    EXPECT_NE(msg.find(p.string() + ": diffuse cache version 3; this build reads versions 1 and 2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("--force"), std::string::npos) << msg;
  }
}

TEST(Cache, CorruptionIsDetected) {
  TempDir dir;
  const fs::path good = dir.path / "good.spd";
  write_diffuse_cache(good, sample_diffuse());
  const std::string b = read_file(good);

  std::string flipped = b;
  flipped[150] ^= 0x10;
  const fs::path crc = dir.write("crc.spd", flipped);
  const std::string crc_msg = error_of([&] { read_diffuse_cache(crc); });
  EXPECT_NE(crc_msg.find("corrupt"), std::string::npos) << crc_msg;
  EXPECT_NE(crc_msg.find(crc.string()), std::string::npos);

  std::string magic = b;
  magic[3] = 'X';
  const fs::path m = dir.write("magic.spd", magic);
  EXPECT_NE(error_of([&] { read_diffuse_cache(m); }).find("expected 'SPUMEDF1'"), std::string::npos);
  EXPECT_NE(error_of([&] { read_fluid_cache(good); }).find("not a spume fluid cache"), std::string::npos);

  for (size_t cut : {size_t(0), size_t(5), size_t(30), size_t(56), size_t(100), size_t(140), b.size() - 1}) {
    const fs::path t = dir.write("cut" + std::to_string(cut) + ".spd", b.substr(0, cut));
    const std::string msg = error_of([&] { read_diffuse_cache(t); });
    EXPECT_NE(msg.find(t.string()), std::string::npos) << cut << ": " << msg;
  }
  const fs::path extra = dir.write("extra.spd", b + "z");
  EXPECT_NE(error_of([&] { read_diffuse_cache(extra); }).find("corrupt"), std::string::npos);
  const fs::path extra_fixed = dir.write("extra_fixed.spd", with_fixed_crc(b + "zzzz"));
  EXPECT_NE(error_of([&] { read_diffuse_cache(extra_fixed); }).find("trailing"), std::string::npos);
  const fs::path raw_extra = dir.write("raw_extra.spd", raw_diffuse_bytes(sample_diffuse()) + "z");
  EXPECT_NE(error_of([&] { read_diffuse_cache(raw_extra); }).find("trailing"), std::string::npos);
}

TEST(Cache, HugeCountFailsBeforeAllocating) {
  TempDir dir;
  const fs::path good = dir.path / "good.spf";
  write_fluid_cache(good, sample_fluid(), 0.01f);
  std::string b = read_file(good);
  put<uint64_t>(b, 28, uint64_t(1) << 60);
  const fs::path p = dir.write("huge.spf", b);
  const std::string msg = error_of([&] { read_fluid_cache(p); });
  EXPECT_NE(msg.find("does not fit the file size"), std::string::npos) << msg;
  EXPECT_NE(error_of([&] { peek_fluid_cache(p); }).find("does not fit"), std::string::npos);

  std::string d = read_file([&] {
    write_diffuse_cache(dir.path / "d.spd", sample_diffuse());
    return dir.path / "d.spd";
  }());
  put<uint64_t>(d, 24, ~uint64_t(0));
  put<uint64_t>(d, 32, ~uint64_t(0));
  put<uint64_t>(d, 40, 0);
  put<uint64_t>(d, 48, 0);
  const fs::path q = dir.write("huge.spd", with_fixed_crc(d));
  EXPECT_NE(error_of([&] { read_diffuse_cache(q); }).find("does not fit"), std::string::npos);
  EXPECT_NE(error_of([&] { peek_diffuse_cache(q); }).find("does not fit"), std::string::npos);
  std::string raw = raw_diffuse_bytes(sample_diffuse());
  put<uint64_t>(raw, 24, uint64_t(1) << 40);
  put<uint64_t>(raw, 32, uint64_t(1) << 40);
  put<uint64_t>(raw, 40, 0);
  put<uint64_t>(raw, 48, 0);
  const fs::path r = dir.write("huge_raw.spd", with_fixed_crc(raw));
  EXPECT_NE(error_of([&] { read_diffuse_cache(r); }).find("does not fit"), std::string::npos);
}

TEST(Cache, InvalidValuesBehindAValidCrcAreRejected) {
  TempDir dir;
  const fs::path good = dir.path / "good.spd";
  write_diffuse_cache(good, sample_diffuse());
  std::string b = raw_diffuse_bytes(sample_diffuse());
  b[b.size() - 4 - 1] = 5;  // last particle's type
  const fs::path t = dir.write("type.spd", with_fixed_crc(b));
  const std::string msg = error_of([&] { read_diffuse_cache(t); });
  EXPECT_NE(msg.find("type 5"), std::string::npos) << msg;
  EXPECT_NE(msg.find(t.string()), std::string::npos);

  std::string counts = read_file(good);
  put<uint64_t>(counts, 32, 1);  // spray 1, foam 2: sums to 4 but disagrees with the data
  put<uint64_t>(counts, 40, 2);
  const fs::path c = dir.write("counts.spd", with_fixed_crc(counts));
  EXPECT_NE(error_of([&] { read_diffuse_cache(c); }).find("header says 1 spray"), std::string::npos);

  const fs::path fgood = dir.path / "good.spf";
  write_fluid_cache(fgood, sample_fluid(), 0.01f);
  std::string f = read_file(fgood);
  put<float>(f, 40 + 12 + 12 + 4, std::numeric_limits<float>::infinity());  // particle 1 y
  const fs::path inf = dir.write("inf.spf", with_fixed_crc(f));
  const std::string inf_msg = error_of([&] { read_fluid_cache(inf); });
  EXPECT_NE(inf_msg.find("particle 1"), std::string::npos) << inf_msg;
  EXPECT_NE(inf_msg.find("non-finite position"), std::string::npos) << inf_msg;

  std::string flags = read_file(fgood);
  put<uint32_t>(flags, 36, 15);
  const fs::path fl = dir.write("flags.spf", with_fixed_crc(flags));
  EXPECT_NE(error_of([&] { read_fluid_cache(fl); }).find("flags 0xf"), std::string::npos);
  EXPECT_EQ(error_of([&] { read_fluid_cache(dir.path / "none.spf"); }), (dir.path / "none.spf").string() + ": no such file");
}

TEST(Cache, LargeDiffuseFramesRoundTripExactlyAcrossChunks) {
  // 2M particles: every column spans several 1 MiB chunks.
  TempDir dir;
  const size_t n = 2'000'000;
  DiffuseFrame d;
  d.resize(n);
  for (size_t i = 0; i < n; ++i) {
    d.ids[i] = diffuse_id(uint32_t(i), 1, 0);
    d.positions[i] = Vec3f(float(i % 100), float(i % 37), 0.5f);
    d.lifetimes[i] = float(i % 1000) * 0.001f;
    d.types[i] = DiffuseType(i % 3);
  }
  const fs::path p = dir.path / "big.spd";
  write_diffuse_cache(p, d);
  const DiffuseFrame e = read_diffuse_cache(p);
  EXPECT_EQ(e.size(), n);
  EXPECT_TRUE(e.positions == d.positions);
  EXPECT_TRUE(e.lifetimes == d.lifetimes);
  EXPECT_TRUE(e.ids == d.ids);
  EXPECT_EQ(e.count_by_type()[2], n / 3);
}

TEST(Cache, TypeCountsAreExactAcrossChunksAndSkipInvalidTypes) {
  // Three chunks of 2^16 and a short fourth; type t at i when i % 7 is t (0, 1, 2), spray otherwise,
  // so the counts follow from the pattern alone. One particle carries an invalid type 3.
  const size_t n = 3 * (size_t(1) << 16) + 17;
  DiffuseFrame d;
  d.resize(n);
  std::array<size_t, 3> expected{};
  for (size_t i = 0; i < n; ++i) {
    const size_t t = i % 7 < 3 ? i % 7 : 0;
    d.types[i] = DiffuseType(t);
    ++expected[t];
  }
  EXPECT_EQ(d.count_by_type(), expected);
  d.types[n - 1] = DiffuseType(3);
  --expected[(n - 1) % 7 < 3 ? (n - 1) % 7 : 0];
  EXPECT_EQ(d.count_by_type(), expected);
}

TEST(Cache, ParallelCrcIsTheSerialCrc) {
  // 9 MiB and 13 bytes: three 4 MiB pieces, the last one short.
  std::vector<unsigned char> bytes((size_t(9) << 20) + 13);
  std::mt19937 rng(5);
  for (unsigned char& b : bytes) b = static_cast<unsigned char>(rng());
  EXPECT_EQ(parallel_crc32(bytes.data(), bytes.size()), crc32_update(crc32_start(), bytes.data(), bytes.size()));
  EXPECT_EQ(parallel_crc32(bytes.data(), 0), crc32_start());
  // "123456789" is the CRC-32 check string: 0xCBF43926.
  EXPECT_EQ(parallel_crc32("123456789", 9), 0xCBF43926u);
}

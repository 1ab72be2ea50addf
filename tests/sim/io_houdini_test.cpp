// Houdini 12+ geometry (binary JSON .bgeo, .bgeo.gz, Blosc .bgeo.sc): real Houdini-written files checked
// against the info block Houdini wrote into each of them, hand-made files for the storages and layouts
// the real ones do not use, and broken copies refused with the file named.
#include <blosc.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <optional>
#include <set>
#include <vector>

#include "sim/io/attribute_names.h"
#include "sim/io/frame_pattern.h"
#include "sim/io/houdini_geometry.h"
#include "sim/io/io_bytes.h"
#include "sim/io/particle_file.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text.h"

namespace spume {
namespace {

using testing::error_of;
using testing::TempDir;
namespace fs = std::filesystem;

using spume::testing::contains;

const fs::path kCopies = fs::path(SPUME_TEST_DATA_DIR) / "houdini";
const fs::path kShared = fs::path(SPUME_SHARED_DATA_DIR) / "houdini_bgeo_sc";

// ---- An independent reading of what Houdini wrote: Blosc chunks decompressed here, then the numbers of
// the info block found by their bytes (the token that defines the key's string, its reference, the value).

uint64_t be64(const std::string& s, size_t at) {
  uint64_t v = 0;
  for (size_t i = 0; i < 8; ++i) v = (v << 8) | uint8_t(s[at + i]);
  return v;
}

std::string unpack_sc(const std::string& file) {
  const size_t end = file.size() - 12 - size_t(be64(file, file.size() - 12));  // the index and its size precede "1fcs"
  std::string out;
  for (size_t pos = 12; pos < end;) {
    size_t nbytes = 0, cbytes = 0, blocksize = 0;
    blosc_cbuffer_sizes(file.data() + pos, &nbytes, &cbytes, &blocksize);
    std::string chunk(nbytes, '\0');
    EXPECT_EQ(blosc_decompress_ctx(file.data() + pos, chunk.data(), nbytes, 1), int(nbytes));
    out += chunk;
    pos += cbytes;
  }
  return out;
}

struct InfoBlock {
  int64_t point_count = -1;
  std::array<double, 6> bounds{};  // xmin xmax ymin ymax zmin zmax
  std::optional<std::array<double, 6>> v_range;  // min x y z, max x y z
};

// The first definition of `key` (0x2b, id, length, bytes), its reference (0x26, id): the offset after them.
size_t after_key(const std::string& json, const std::string& key) {
  const size_t at = json.find(std::string(1, char(key.size())) + key);
  EXPECT_NE(at, std::string::npos) << key;
  if (at == std::string::npos) return 0;
  const size_t ref = at + 1 + key.size();
  EXPECT_EQ(uint8_t(json[ref]), 0x26) << key;
  EXPECT_EQ(json[ref + 1], json[at - 1]) << key;  // the id just defined
  return ref + 2;
}

InfoBlock info_block_of(const std::string& json) {
  InfoBlock b;
  size_t at = after_key(json, "pointcount");
  const uint8_t kind = uint8_t(json[at]);
  const char* p = json.data() + at + 1;
  b.point_count = kind == 0x11 ? int64_t(int8_t(*p)) : kind == 0x12 ? io::load<int16_t>(p, io::Endian::Little)
                  : kind == 0x13 ? io::load<int32_t>(p, io::Endian::Little) : io::load<int64_t>(p, io::Endian::Little);
  at = after_key(json, "bounds");
  EXPECT_EQ(json.substr(at, 3), std::string("\x40\x19\x06", 3));  // a uniform array of 6 real32
  for (int i = 0; i < 6; ++i) b.bounds[size_t(i)] = io::load<float>(json.data() + at + 3 + 4 * i, io::Endian::Little);
  const size_t v = json.find("'point v':(");
  if (v != std::string::npos) {
    std::array<double, 6> r{};
    const char* s = json.c_str() + v + 11;
    for (double& x : r) {
      char* end = nullptr;
      x = std::strtod(s, &end);
      s = end + 1;  // past the comma
    }
    b.v_range = r;
  }
  return b;
}

std::vector<fs::path> real_files() {
  std::vector<fs::path> files;
  for (const fs::path& dir : {kCopies, kShared / "splatter", kShared / "retime", kShared / "physics_painter"}) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (io::ends_with(e.path().string(), ".bgeo.sc")) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The independent reading itself, checked on numbers read off the files with a hex dump and a Python
// decoder of the binary JSON: retime frame 10 (tests/data/houdini), and splatter frame 15 when present.
TEST(HoudiniGeometry, TheIndependentInfoReaderReadsWhatTheFilesSay) {
  const InfoBlock retime = info_block_of(unpack_sc(testing::read_file(kCopies / "retime_demoscene.10.bgeo.sc")));
  EXPECT_EQ(retime.point_count, 30);
  EXPECT_EQ(retime.bounds[0], -1.0000003576278687);
  EXPECT_EQ(retime.bounds[3], 3.169647693634033);
  ASSERT_TRUE(retime.v_range);
  EXPECT_EQ((*retime.v_range)[1], -13.622340202331543);
  const fs::path splatter = kShared / "splatter/splatter_demoscene.15.bgeo.sc";
  if (!fs::exists(splatter)) GTEST_SKIP() << "no " << splatter << " (the shared data folder)";
  const InfoBlock s = info_block_of(unpack_sc(testing::read_file(splatter)));
  EXPECT_EQ(s.point_count, 13883);
  EXPECT_EQ(s.bounds[1], 2.7389681339263916);
  EXPECT_EQ(s.bounds[4], -1.947072982788086);
  ASSERT_TRUE(s.v_range);
  EXPECT_EQ((*s.v_range)[5], 2.6965923309326172);
}

// Every real file: the point count, the bounds and the range of v that Houdini wrote in its info block.
// The info bounds cover the whole geometry: for splatter (points and polygons) they are the points'
// bounds exactly; retime's and physics_painter's include packed objects, which hold the points.
TEST(HoudiniGeometry, RealFilesAgreeWithTheirOwnInfoBlock) {
  const std::vector<fs::path> files = real_files();
  ASSERT_GE(files.size(), 3u);
  if (files.size() < 36) std::printf("note: %zu files (the shared data folder adds 33)\n", files.size());
  for (const fs::path& path : files) {
    SCOPED_TRACE(path.string());
    const InfoBlock expected = info_block_of(unpack_sc(testing::read_file(path)));
    HoudiniGeometryInfo info;
    const FluidFrame frame = read_houdini_geometry(path, &info);
    EXPECT_EQ(int64_t(info.point_count), expected.point_count);
    const Aabb& b = info.point_bounds;
    const std::array<double, 6> got = {b.min.x(), b.max.x(), b.min.y(), b.max.y(), b.min.z(), b.max.z()};
    const bool splatter = contains(path.filename().string(), "splatter");
    for (size_t k = 0; k < 6; ++k) {
      if (splatter) EXPECT_EQ(got[k], expected.bounds[k]) << "bound " << k;
      else if (k % 2 == 0) EXPECT_GE(got[k], expected.bounds[k]) << "bound " << k;
      else EXPECT_LE(got[k], expected.bounds[k]) << "bound " << k;
    }
    if (expected.v_range) {
      const Aabb& v = info.velocity_range;
      const std::array<double, 6> range = {v.min.x(), v.min.y(), v.min.z(), v.max.x(), v.max.y(), v.max.z()};
      for (size_t k = 0; k < 6; ++k) EXPECT_EQ(range[k], float((*expected.v_range)[k])) << "v range " << k;
      EXPECT_EQ(frame.velocities.size(), frame.size());
    }
    if (splatter) {
      // 1009 particles (ids 0..1008, read with the Python decoder; frame 15's point group of emitted
      // points also holds 1009); the other 12874 points are the splatter surface's, whose id is -1.
      EXPECT_EQ(frame.size(), 1009u);
      EXPECT_EQ(info.points_without_id, 12874u);
      EXPECT_EQ(std::set<uint32_t>(frame.ids.begin(), frame.ids.end()).size(), frame.size());
      for (const Vec3f& x : frame.positions) EXPECT_TRUE((x.array() >= b.min.array()).all() && (x.array() <= b.max.array()).all());
    } else {
      EXPECT_EQ(frame.size(), info.point_count);  // no negative ids: every point
    }
    if (contains(path.filename().string(), "retime")) {
      EXPECT_EQ(std::set<uint32_t>(frame.ids.begin(), frame.ids.end()).size(), 30u);
      EXPECT_EQ(info.velocity_attribute, "v");
    }
  }
}

// ---- Hand-made files: a binary JSON writer.

struct Json {
  io::Endian e = io::Endian::Little;
  std::string b = "\x7fNSJb";
  explicit Json(io::Endian endian = io::Endian::Little) : e(endian), b(e == io::Endian::Little ? "\x7fNSJb" : "\x7f" "bJSN") {}
  void len(uint64_t n) {
    if (n < 0xf1) {
      b += char(n);
    } else {
      b += char(0xf4);
      io::store(b, uint32_t(n), e);
    }
  }
  Json& open() { return b += '[', *this; }
  Json& close() { return b += ']', *this; }
  Json& s(const std::string& text) {
    b += '\x27';
    len(text.size());
    b += text;
    return *this;
  }
  Json& i8(int v) { return b += '\x11', b += char(int8_t(v)), *this; }
  Json& f32(float v) { return b += '\x19', io::store(b, v, e), *this; }
  template <typename T>
  Json& uniform(char code, const std::vector<T>& v) {
    b += '\x40';
    b += code;
    len(v.size());
    for (T x : v) io::store(b, x, e);
    return *this;
  }
  Json& bits(const std::vector<bool>& v) {
    b += "\x40\x10";
    len(v.size());
    for (size_t w = 0; w < (v.size() + 31) / 32; ++w) {
      uint32_t word = 0;
      for (size_t i = 0; i < 32 && w * 32 + i < v.size(); ++i) word |= uint32_t(v[w * 32 + i]) << i;
      io::store(b, word, e);
    }
    return *this;
  }
};

// One point attribute: [definition, body] with the value block written by `values`.
template <typename Values>
void attribute(Json& j, const std::string& name, int size, const std::string& storage, Values&& values) {
  j.open().open().s("scope").s("public").s("type").s("numeric").s("name").s(name).close();
  j.open().s("size").i8(size).s("storage").s(storage).s("values").open().s("size").i8(size).s("storage").s(storage);
  values(j);
  j.close().close().close();
}

// Five points in pages of 2 (Houdini's pages hold 1024), every layout and several storages:
//   P  fpreal64, packed as [x][y z], constant flags x: page 0 and 2, yz: page 1, so the data is
//      page 0: x 10, yz (20 30) (21 31); page 1: x 12, 13, yz (22 32); page 2: x 14, yz (24 34)
//      giving (10 20 30) (10 21 31) (12 22 32) (13 22 32) (14 24 34) (worked by hand)
//   v  "tuples" of plain numbers: (i, -i, 0.5)
//   id int64 as "arrays": -1 7 9 3 5 (the first point has no id, so it is not a particle)
std::string five_points() {
  Json j;
  j.open().s("fileversion").s("19.5.0").s("pointcount").i8(5).s("info");
  j.b += '{';
  j.s("bounds").uniform<float>('\x19', {10, 14, 20, 24, 30, 34});
  j.b += '}';
  j.s("attributes").open().s("pointattributes").open();
  attribute(j, "P", 3, "fpreal64", [](Json& k) {
    k.s("pagesize").i8(2).s("packing").uniform<int32_t>('\x13', {1, 2}).s("constantpageflags").open();
    k.bits({true, false, true}).bits({false, true, false}).close();
    k.s("rawpagedata").uniform<double>('\x1a', {10, 20, 30, 21, 31, 12, 13, 22, 32, 14, 24, 34});
  });
  attribute(j, "v", 3, "fpreal32", [](Json& k) {
    k.s("tuples").open();
    for (int i = 0; i < 5; ++i) k.open().f32(float(i)).f32(float(-i)).f32(0.5f).close();
    k.close();
  });
  attribute(j, "id", 1, "int64", [](Json& k) { k.s("arrays").open().uniform<int64_t>('\x14', {-1, 7, 9, 3, 5}).close(); });
  j.close().close().close();
  return j.b;
}

// Two points whose velocity, id and mass are named `v`, `id` and `mass`: P (1 2 3) (4 5 6), velocity
// (i, -i, 0.5), ids 7 and 9, masses 0.5.
std::string two_points_named(const std::string& v, const std::string& id, const std::string& mass) {
  Json j;
  j.open().s("fileversion").s("19.5.0").s("pointcount").i8(2).s("attributes").open().s("pointattributes").open();
  attribute(j, "P", 3, "fpreal32", [](Json& k) {
    k.s("tuples").open().open().f32(1).f32(2).f32(3).close().open().f32(4).f32(5).f32(6).close().close();
  });
  attribute(j, v, 3, "fpreal32", [](Json& k) {
    k.s("tuples").open();
    for (int i = 0; i < 2; ++i) k.open().f32(float(i)).f32(float(-i)).f32(0.5f).close();
    k.close();
  });
  attribute(j, id, 1, "int64", [](Json& k) { k.s("arrays").open().uniform<int64_t>('\x14', {7, 9}).close(); });
  attribute(j, mass, 1, "fpreal32", [](Json& k) { k.s("arrays").open().uniform<float>('\x19', {0.5f, 0.5f}).close(); });
  j.close().close().close();
  return j.b;
}

// A .bgeo.sc around `json`: "scf1", 8 zero bytes, Blosc chunks of at most `chunk` bytes, the index.
std::string scf(const std::string& json, size_t chunk) {
  std::string out = std::string("scf1") + std::string(8, '\0');
  std::vector<uint64_t> index;
  for (size_t at = 0; at < json.size(); at += chunk) {
    const size_t n = std::min(chunk, json.size() - at);
    std::string c(n + BLOSC_MAX_OVERHEAD, '\0');
    const int size = blosc_compress_ctx(5, 1, 4, n, json.data() + at, c.data(), c.size(), "lz4", 0, 1);
    EXPECT_GT(size, 0);
    if (at > 0) index.push_back(out.size() - 12);
    out += c.substr(0, size_t(size));
  }
  index.push_back(chunk);
  index.push_back(json.size() % chunk ? json.size() % chunk : chunk);
  for (uint64_t x : index) io::store(out, x, io::Endian::Big);
  io::store(out, uint64_t(index.size() * 8), io::Endian::Big);
  return out + "1fcs";
}

TEST(HoudiniGeometry, PagedPackedConstantTuplesAndArraysInEveryContainer) {
  TempDir dir;
  const std::string json = five_points();
  for (const fs::path& p : {dir.write("a.bgeo", json), dir.write("b.bgeo.gz", io::gzip_compress(json)),
                            dir.write("c.bgeo.sc", scf(json, 64)), dir.write("d.BGEO.SC", scf(json, 1 << 20))}) {
    SCOPED_TRACE(p.string());
    EXPECT_EQ(particle_format(p), ParticleFormat::HoudiniGeometry);
    HoudiniGeometryInfo info;
    const FluidFrame f = read_houdini_geometry(p, &info);
    EXPECT_EQ(info.point_count, 5u);
    EXPECT_EQ(info.points_without_id, 1u);
    ASSERT_EQ(f.size(), 4u);
    const std::vector<Vec3f> positions = {{10, 21, 31}, {12, 22, 32}, {13, 22, 32}, {14, 24, 34}};
    const std::vector<uint32_t> ids = {7, 9, 3, 5};
    for (size_t i = 0; i < 4; ++i) {
      EXPECT_EQ(f.positions[i], positions[i]) << i;
      EXPECT_EQ(f.velocities[i], Vec3f(float(i + 1), -float(i + 1), 0.5f)) << i;
      EXPECT_EQ(f.ids[i], ids[i]) << i;
    }
    EXPECT_EQ(info.point_bounds.min, Vec3f(10, 20, 30));  // the left-out point counts in the file's bounds
    EXPECT_EQ(read_fluid_file(p).size(), 4u);
    EXPECT_TRUE(contains(describe_particle_file(p), "left out: 1 points with a negative id")) << describe_particle_file(p);
  }
}

// Every name of the one attribute table (io/attribute_names.h) is read as its attribute.
TEST(HoudiniGeometry, ReadsEveryNameOfTheAttributeTable) {
  TempDir dir;
  const auto velocity = io::attribute_names(io::AttributeRole::Velocity), id = io::attribute_names(io::AttributeRole::Id),
             mass = io::attribute_names(io::AttributeRole::Mass);
  for (size_t k = 0; k < std::max({velocity.size(), id.size(), mass.size()}); ++k) {
    const std::string v(velocity[k % velocity.size()]), i(id[k % id.size()]), m(mass[k % mass.size()]);
    SCOPED_TRACE(v + ", " + i + ", " + m);
    HoudiniGeometryInfo info;
    const FluidFrame f = read_houdini_geometry(dir.write("k" + std::to_string(k) + ".bgeo", two_points_named(v, i, m)), &info);
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(info.velocity_attribute, v);
    EXPECT_EQ(f.velocities, (std::vector<Vec3f>{Vec3f(0, 0, 0.5f), Vec3f(1, -1, 0.5f)}));
    EXPECT_EQ(f.ids, (std::vector<uint32_t>{7, 9}));
    EXPECT_EQ(f.masses, (std::vector<float>{0.5f, 0.5f}));
  }
}

// The storages the real files do not use, in a file written big-endian ("bJSN"):
//   P    fpreal16 paged: halves 0.5 1.5 -2 | 0.25 3 0 | 1 2 -0.5 (exact in half precision)
//   vel  int16 as arrays (one per component): x 1 -2 3, y 300 0 -300, z 7 8 9
//   id   uint16 paged: 10 65535 3;  mass uint8 paged: 1 2 200
TEST(HoudiniGeometry, SmallStoragesBigEndianAndTheVelocityNamedVel) {
  Json j(io::Endian::Big);
  j.open().s("pointcount").i8(3).s("attributes").open().s("pointattributes").open();
  const std::vector<uint16_t> halves = {0x3800, 0x3e00, 0xc000, 0x3400, 0x4200, 0x0000, 0x3c00, 0x4000, 0xb800};
  attribute(j, "P", 3, "fpreal16", [&](Json& k) { k.s("pagesize").i8(64).s("rawpagedata").uniform<uint16_t>('\x18', halves); });
  attribute(j, "vel", 3, "int16", [](Json& k) {
    k.s("arrays").open().uniform<int16_t>('\x12', {1, -2, 3}).uniform<int16_t>('\x12', {300, 0, -300});
    k.uniform<int16_t>('\x12', {7, 8, 9}).close();
  });
  attribute(j, "id", 1, "uint16", [](Json& k) { k.s("pagesize").i8(64).s("rawpagedata").uniform<uint16_t>('\x22', {10, 65535, 3}); });
  attribute(j, "mass", 1, "uint8", [](Json& k) { k.s("pagesize").i8(64).s("rawpagedata").uniform<uint8_t>('\x21', {1, 2, 200}); });
  j.close().close().close();
  TempDir dir;
  HoudiniGeometryInfo info;
  const FluidFrame f = read_houdini_geometry(dir.write("small.bgeo", j.b), &info);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f.positions[0], Vec3f(0.5f, 1.5f, -2.0f));
  EXPECT_EQ(f.positions[1], Vec3f(0.25f, 3.0f, 0.0f));
  EXPECT_EQ(f.positions[2], Vec3f(1.0f, 2.0f, -0.5f));
  EXPECT_EQ(info.velocity_attribute, "vel");
  EXPECT_EQ(f.velocities[0], Vec3f(1, 300, 7));
  EXPECT_EQ(f.velocities[2], Vec3f(3, -300, 9));
  EXPECT_EQ(f.ids, (std::vector<uint32_t>{10, 65535, 3}));
  EXPECT_EQ(f.masses, (std::vector<float>{1, 2, 200}));
  // A velocity of the wrong size is refused by name.
  Json w;
  w.open().s("pointcount").i8(1).s("attributes").open().s("pointattributes").open();
  attribute(w, "P", 3, "fpreal32", [](Json& k) { k.s("tuples").open().open().f32(0).f32(0).f32(0).close().close(); });
  attribute(w, "v", 2, "fpreal32", [](Json& k) { k.s("tuples").open().open().f32(0).f32(0).close().close(); });
  w.close().close().close();
  const fs::path bad = dir.write("v2.bgeo", w.b);
  const std::string msg = error_of([&] { read_fluid_file(bad); });
  EXPECT_TRUE(contains(msg, bad.string() + ": point attribute 'v' has 2 components; a velocity needs 3")) << msg;
}

// Masses of -1 (Houdini's "not set"; a skinning demo's 11 files hold them): read as the file holds them,
// and described as odd, where they used to make every reader refuse the file.
TEST(HoudiniGeometry, MassesOfMinusOneAreReadAsTheyAreAndDescribedAsOdd) {
  Json j;
  j.open().s("pointcount").i8(3).s("attributes").open().s("pointattributes").open();
  attribute(j, "P", 3, "fpreal32", [](Json& k) {
    k.s("tuples").open().open().f32(0).f32(0).f32(0).close().open().f32(0.04f).f32(0).f32(0).close();
    k.open().f32(0.08f).f32(0).f32(0).close().close();
  });
  attribute(j, "mass", 1, "fpreal32",
            [](Json& k) { k.s("tuples").open().open().f32(-1).close().open().f32(0.5f).close().open().f32(-1).close().close(); });
  j.close().close().close();
  TempDir dir;
  const fs::path p = dir.write("masses.bgeo", j.b);
  EXPECT_EQ(read_fluid_file(p).masses, (std::vector<float>{-1, 0.5f, -1}));
  const std::string d = describe_particle_file(p);
  EXPECT_TRUE(contains(d, "masses: -1 .. 0.5 kg")) << d;
  EXPECT_TRUE(contains(d, "odd: 2 of 3 masses are not > 0 (-1 kg)")) << d;
}

// ---- Broken input: refused with the file named, never a crash, nothing decompressed beyond the headers.

TEST(HoudiniGeometry, TruncatedAndCorruptedCopiesAreRefusedNamingTheFile) {
  TempDir dir;
  const std::string file = testing::read_file(kCopies / "retime_demoscene.10.bgeo.sc");
  ASSERT_GT(file.size(), 40000u);
  for (size_t cut : {size_t(0), size_t(3), size_t(12), size_t(27), size_t(1000), file.size() / 2, file.size() - 29,
                     file.size() - 13, file.size() - 12, file.size() - 1}) {
    const fs::path p = dir.write("cut.bgeo.sc", file.substr(0, cut));
    const std::string msg = error_of([&] { read_fluid_file(p); });
    EXPECT_TRUE(contains(msg, p.string() + ": ")) << cut << ": " << msg;
    EXPECT_TRUE(contains(msg, "truncated") || contains(msg, "corrupt") || contains(msg, "must start with 'scf1'"))
        << cut << ": " << msg;
  }
  // A chunk header claiming far more than the file could hold: refused before anything is decompressed.
  std::string bomb = file;
  for (size_t i = 0; i < 4; ++i) bomb[12 + 4 + i] = char(i == 3 ? 0x7f : 0xff);  // nbytes = 2^31 - 1
  std::string msg = error_of([&] { read_fluid_file(dir.write("bomb.bgeo.sc", bomb)); });
  EXPECT_TRUE(contains(msg, "claims 2147483647 decompressed bytes from")) << msg;
  EXPECT_TRUE(contains(msg, "(LZ4), more than its codec can hold in them (256 to 1, its densest)")) << msg;

  // The binary JSON inside, cut anywhere or with any byte changed: an Error naming the file, or (for a
  // changed number) a frame; never a crash.
  const std::string json = unpack_sc(file);
  const fs::path p = dir.path / "j.bgeo";
  for (size_t k = 1; k < 200; ++k) {
    const size_t at = json.size() * k / 200;
    std::ofstream(p, std::ios::binary | std::ios::trunc) << json.substr(0, at);
    msg = error_of([&] { read_fluid_file(p); });
    EXPECT_TRUE(contains(msg, p.string() + ": ")) << at << ": " << msg;
    std::string changed = json;
    changed[at] = char(changed[at] ^ 0x5a);
    std::ofstream(p, std::ios::binary | std::ios::trunc) << changed;
    try {
      read_fluid_file(p);
    } catch (const Error& e) {
      EXPECT_TRUE(contains(e.what(), p.string() + ": ")) << e.what();
    }
  }
}

// Houdini names cache frames with $F (no padding) or $F4 (4 digits); other $F... variables stay text.
TEST(HoudiniGeometry, FramePatternsTakeHoudinisFrameVariable) {
  EXPECT_EQ(expand_frame_pattern("geo/flip.$F4.bgeo.sc", 7), "geo/flip.0007.bgeo.sc");
  EXPECT_EQ(expand_frame_pattern("geo/flip.$F.bgeo.sc", 12), "geo/flip.12.bgeo.sc");
  EXPECT_EQ(expand_frame_pattern("geo/$FPS_$F2.bgeo.sc", 3), "geo/$FPS_03.bgeo.sc");
  EXPECT_TRUE(is_frame_pattern("a.$F.bgeo"));
  EXPECT_FALSE(is_frame_pattern("a.$FF.bgeo"));
  EXPECT_TRUE(contains(error_of([] { expand_frame_pattern("a.$F.%d.bgeo", 1); }), "more than one frame placeholder"));
  TempDir dir;
  for (const char* name : {"c.0009.bgeo.sc", "c.0010.bgeo.sc", "c.10.bgeo.sc"}) dir.touch(name);
  EXPECT_EQ(find_pattern_frames((dir.path / "c.$F4.bgeo.sc").string()), (std::vector<int>{9, 10}));
  EXPECT_EQ(find_pattern_frames((dir.path / "c.$F.bgeo.sc").string()), (std::vector<int>{10}));
}

}  // namespace
}  // namespace spume

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numeric>

#include "sim/core/error.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"
#include "sim/io/attribute_names.h"
#include "sim/io/bgeo.h"
#include "sim/io/io_bytes.h"

namespace fs = std::filesystem;
using namespace spume;
using namespace spume::testing;

namespace {

const fs::path kRealFrame = fs::path(SPUME_TEST_DATA_DIR) / "splishsplash_rest_30192.bgeo";

// Big-endian bytes, written independently of the reader's helpers.
struct Be {
  std::string b;
  Be& u32(uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) b += char((v >> s) & 0xff);
    return *this;
  }
  Be& i32(int32_t v) { return u32(uint32_t(v)); }
  Be& u16(uint16_t v) {
    b += char(v >> 8);
    b += char(v & 0xff);
    return *this;
  }
  Be& f32(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u32(u);
  }
  Be& raw(std::string_view s) {
    b += s;
    return *this;
  }
  Be& attr(std::string_view name, uint16_t size, int32_t type) {
    u16(uint16_t(name.size())).raw(name).u16(size).i32(type);
    for (int k = 0; k < size; ++k) i32(0);
    return *this;
  }
};

// Header of a hand-made file: counts = points, prims, point groups, prim groups, point attrs,
// vertex attrs, prim attrs, detail attrs.
Be header(int points, int point_attrs, int detail_attrs = 0) {
  Be h;
  h.raw("BgeoV").i32(5);
  for (int c : {points, 0, 0, 0, point_attrs, 0, 0, detail_attrs}) h.i32(c);
  return h;
}

}  // namespace

TEST(Bgeo, ReadsRealSplishSplashFrame) {
  BgeoInfo info;
  const FluidFrame f = read_bgeo(kRealFrame, &info);
  ASSERT_EQ(f.size(), 30192u);
  EXPECT_TRUE(info.gzipped);
  EXPECT_EQ(info.version, 5);
  ASSERT_EQ(info.point_attributes.size(), 3u);
  EXPECT_EQ(info.point_attributes[0].name, "id");
  EXPECT_EQ(info.point_attributes[0].type, "int");
  EXPECT_EQ(info.point_attributes[1].name, "velocity");
  EXPECT_EQ(info.point_attributes[1].components, 3);
  EXPECT_EQ(info.point_attributes[2].name, "density");
  EXPECT_FALSE(info.trailing_data_skipped);
  ASSERT_TRUE(f.has_ids());
  ASSERT_TRUE(f.has_velocities());
  EXPECT_TRUE(f.masses.empty());

  // The ids are a permutation of 0..30191 (checked with Python: min 0, max 30191, 30192 distinct).
  std::vector<uint32_t> ids = f.ids;
  std::sort(ids.begin(), ids.end());
  std::vector<uint32_t> expected(30192);
  std::iota(expected.begin(), expected.end(), 0u);
  EXPECT_EQ(ids, expected);

  // Expected values from an independent Python decode of the file:
  //   d = gzip.open(path).read(); point i at 102 + 36*i: struct.unpack_from('>ffffiffff', d, ...)
  // giving bounds min (-1.9100000858306885, 0.08999019116163254, -0.6599999666213989),
  // max (-0.9900001287460327, 1.5299901962280273, 0.6600000262260437), and point 0 =
  // (-1.8700001239776611, 0.08999019116163254, 0.10000001639127731), id 1277, v (0, -0.00981, 0).
  Aabb b;
  for (const Vec3f& p : f.positions) b.extend(p);
  EXPECT_FLOAT_EQ(b.min.x(), -1.9100000858306885f);
  EXPECT_FLOAT_EQ(b.min.y(), 0.08999019116163254f);
  EXPECT_FLOAT_EQ(b.min.z(), -0.6599999666213989f);
  EXPECT_FLOAT_EQ(b.max.x(), -0.9900001287460327f);
  EXPECT_FLOAT_EQ(b.max.y(), 1.5299901962280273f);
  EXPECT_FLOAT_EQ(b.max.z(), 0.6600000262260437f);
  EXPECT_EQ(info.bounds.min, b.min);
  EXPECT_EQ(info.bounds.max, b.max);
  EXPECT_FLOAT_EQ(f.positions[0].x(), -1.8700001239776611f);
  EXPECT_FLOAT_EQ(f.positions[0].z(), 0.10000001639127731f);
  EXPECT_EQ(f.ids[0], 1277u);
  EXPECT_FLOAT_EQ(f.velocities[0].y(), -0.009810000658035278f);
  EXPECT_EQ(f.velocities[0].x(), 0.0f);
  EXPECT_EQ(f.ids[30191], 30175u);
}

TEST(Bgeo, ReadsHandBuiltUncompressedFileWithAllAttributeKinds) {
  TempDir dir;
  // Attributes: mass float[1], name indexed string (2 strings), v vector[3], id int[1]; one detail float.
  Be f = header(2, 4, 1);
  f.attr("mass", 1, 0);
  f.u16(4).raw("name").u16(1).i32(4).i32(2).u16(3).raw("abc").u16(1).raw("d");
  f.attr("v", 3, 5).attr("id", 1, 1);
  f.f32(1.5f).f32(-2).f32(3).f32(1).f32(0.25f).i32(1).f32(4).f32(5).f32(6).i32(7);
  f.f32(0).f32(0).f32(-1).f32(1).f32(0.5f).i32(0).f32(-4).f32(0).f32(0).i32(3);
  f.attr("timestep", 1, 0).f32(0.04f);
  f.raw(std::string("\x00\xff", 2));
  const fs::path p = dir.write("hand.bgeo", f.b);

  BgeoInfo info;
  const FluidFrame frame = read_bgeo(p, &info);
  EXPECT_FALSE(info.gzipped);
  ASSERT_EQ(frame.size(), 2u);
  EXPECT_EQ(frame.positions[0], Vec3f(1.5f, -2, 3));
  EXPECT_EQ(frame.positions[1], Vec3f(0, 0, -1));
  EXPECT_EQ(frame.velocities[0], Vec3f(4, 5, 6));
  EXPECT_EQ(frame.velocities[1], Vec3f(-4, 0, 0));
  EXPECT_EQ(frame.ids, (std::vector<uint32_t>{7, 3}));
  EXPECT_EQ(frame.masses, (std::vector<float>{0.25f, 0.5f}));
  ASSERT_EQ(info.point_attributes.size(), 4u);
  EXPECT_EQ(info.point_attributes[1].type, "index");
  ASSERT_EQ(info.detail_attributes.size(), 1u);
  EXPECT_EQ(info.detail_attributes[0].name, "timestep");
  EXPECT_EQ(info.bounds.min, Vec3f(0, -2, -1));
}

// Every name of the one attribute table (io/attribute_names.h) is read as its attribute; the k-th
// file spells the velocity, the id and the mass with the k-th name of each.
TEST(Bgeo, ReadsEveryNameOfTheAttributeTable) {
  TempDir dir;
  const auto velocity = io::attribute_names(io::AttributeRole::Velocity), id = io::attribute_names(io::AttributeRole::Id),
             mass = io::attribute_names(io::AttributeRole::Mass);
  for (size_t k = 0; k < std::max({velocity.size(), id.size(), mass.size()}); ++k) {
    const std::string_view v_name = velocity[k % velocity.size()], id_name = id[k % id.size()],
                           m_name = mass[k % mass.size()];
    SCOPED_TRACE(std::string(v_name) + ", " + std::string(id_name) + ", " + std::string(m_name));
    Be f = header(1, 3);
    f.attr(m_name, 1, 0).attr(v_name, 3, 5).attr(id_name, 1, 1);
    f.f32(1).f32(2).f32(3).f32(1).f32(0.5f).f32(4).f32(5).f32(6).i32(9);
    f.raw(std::string("\x00\xff", 2));
    const FluidFrame frame = read_bgeo(dir.write("k" + std::to_string(k) + ".bgeo", f.b));
    ASSERT_EQ(frame.size(), 1u);
    EXPECT_EQ(frame.velocities, (std::vector<Vec3f>{Vec3f(4, 5, 6)}));
    EXPECT_EQ(frame.ids, (std::vector<uint32_t>{9}));
    EXPECT_EQ(frame.masses, (std::vector<float>{0.5f}));
  }
}

TEST(Bgeo, FluidRoundTripIsGzipped) {
  TempDir dir;
  FluidFrame f;
  f.positions = {Vec3f(0.1f, 0.2f, 0.3f), Vec3f(-1, 2, 1e-3f), Vec3f(5, 5, 5)};
  f.velocities = {Vec3f(1, 0, 0), Vec3f(0, -9.81f, 0), Vec3f(0.5f, 0.25f, 0.125f)};
  f.ids = {42, 0, 2147483647u};
  f.masses = {0.008f, 0.008f, 0.009f};
  const fs::path p = dir.path / "out" / "fluid.bgeo";
  write_bgeo(p, f);
  const std::string bytes = read_file(p);
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(uint8_t(bytes[0]), 0x1f);
  EXPECT_EQ(uint8_t(bytes[1]), 0x8b);
  const std::string raw = io::gunzip(bytes, "test");
  EXPECT_EQ(raw.substr(0, 5), "BgeoV");
  EXPECT_EQ(raw.substr(raw.size() - 2), std::string("\x00\xff", 2));
  const FluidFrame g = read_bgeo(p);
  EXPECT_EQ(g.positions, f.positions);
  EXPECT_EQ(g.velocities, f.velocities);
  EXPECT_EQ(g.ids, f.ids);
  EXPECT_EQ(g.masses, f.masses);

  FluidFrame bare;
  bare.positions = {Vec3f(1, 2, 3)};
  write_bgeo(p, bare);
  const FluidFrame h = read_bgeo(p);
  EXPECT_EQ(h.positions, bare.positions);
  EXPECT_FALSE(h.has_ids());
  EXPECT_FALSE(h.has_velocities());

  write_bgeo(p, FluidFrame{});
  EXPECT_EQ(read_bgeo(p).size(), 0u);
}

TEST(Bgeo, DiffuseRoundTrip) {
  TempDir dir;
  DiffuseFrame d;
  d.positions = {Vec3f(0, 1, 2), Vec3f(3, 4, 5), Vec3f(-1, -1, -1)};
  d.velocities = {Vec3f(1, 1, 1), Vec3f(0, 0, 0), Vec3f(-2, 0, 3)};
  d.lifetimes = {1.5f, 0.0f, 7.25f};
  d.types = {DiffuseType::Spray, DiffuseType::Foam, DiffuseType::Bubble};
  d.ids = {diffuse_id(30191, 17, 3), diffuse_id(0, kMaxBirthStep, kMaxSamplesPerStep), diffuse_id(4000000000u, 0, 0)};
  const fs::path p = dir.path / "diffuse.bgeo";
  write_bgeo(p, d);
  const BgeoInfo info = read_bgeo_info(p);
  std::vector<std::string> names;
  for (const auto& a : info.point_attributes) names.push_back(a.name);
  EXPECT_EQ(names, (std::vector<std::string>{"v", "type", "lifetime", "id", "birth", "sample"}));
  const DiffuseFrame e = read_bgeo_diffuse(p);
  EXPECT_EQ(e.positions, d.positions);
  EXPECT_EQ(e.velocities, d.velocities);
  EXPECT_EQ(e.lifetimes, d.lifetimes);
  EXPECT_EQ(e.types, d.types);
  EXPECT_EQ(e.ids, d.ids);
}

// The diffuse export's point groups, byte by byte as SideFX's GPD library (the V5 reference) lays them
// out after the detail block: uint16 name length, name, int32 bit count, big-endian uint32 mask words
// with point i at bit i & 31 of word i >> 5. 35 points: spray at 0, 2 and 33; bubbles at 1 and 34.
TEST(Bgeo, DiffuseExportCarriesAPointGroupPerTypeAsGpdWritesThem) {
  TempDir dir;
  DiffuseFrame d;
  d.resize(35);
  for (size_t i = 0; i < 35; ++i) {
    d.positions[i] = Vec3f(float(i), 0, 0), d.velocities[i] = Vec3f::Zero(), d.lifetimes[i] = 1.0f;
    d.types[i] = DiffuseType::Foam, d.ids[i] = i;
  }
  for (size_t i : {0, 2, 33}) d.types[i] = DiffuseType::Spray;
  for (size_t i : {1, 34}) d.types[i] = DiffuseType::Bubble;
  const fs::path p = dir.path / "groups.bgeo";
  write_bgeo(p, d);
  const std::string raw = io::gunzip(read_file(p), "test");
  Be groups;
  groups.u16(5).raw("spray").i32(35).u32(0b101).u32(0b10);
  groups.u16(4).raw("foam").i32(35).u32(0xFFFFFFFFu & ~0b111u).u32(0b001);
  groups.u16(6).raw("bubble").i32(35).u32(0b010).u32(0b100);
  const std::string tail = groups.b + std::string("\x00\xff", 2);
  ASSERT_GE(raw.size(), tail.size());
  EXPECT_EQ(raw.substr(raw.size() - tail.size()), tail);
  EXPECT_EQ(raw.substr(17, 4), std::string("\x00\x00\x00\x03", 4)) << "the header counts 3 point groups";
  const BgeoInfo info = read_bgeo_info(p);
  EXPECT_FALSE(info.trailing_data_skipped);
  using Group = std::pair<std::string, size_t>;
  EXPECT_EQ(info.point_groups, (std::vector<Group>{{"spray", 3}, {"foam", 30}, {"bubble", 2}}));
  EXPECT_EQ(read_bgeo_diffuse(p).types, d.types);
}

// A hand-made file with an ordered point group (flag byte 01, then the order, a negative index
// followed by its profile) and a primitive group over no primitives: read through to the end marker.
TEST(Bgeo, ReadsOrderedAndPrimitiveGroups) {
  TempDir dir;
  Be f;
  f.raw("BgeoV").i32(5);
  for (int c : {2, 0, 1, 1, 0, 0, 0, 0}) f.i32(c);
  f.f32(1).f32(2).f32(3).f32(1).f32(4).f32(5).f32(6).f32(1);
  f.raw("\x01").u16(3).raw("sel").i32(2).u32(0b11).i32(2).i32(1).i32(-1).i32(7);
  f.u16(5).raw("prims").i32(0);
  f.raw(std::string("\x00\xff", 2));
  const fs::path p = dir.write("ordered.bgeo", f.b);
  const BgeoInfo info = read_bgeo_info(p);
  ASSERT_EQ(info.point_groups.size(), 1u);
  EXPECT_EQ(info.point_groups[0], (std::pair<std::string, size_t>{"sel", 2}));
  EXPECT_EQ(read_bgeo(p).size(), 2u);
  // A mask for the wrong number of points is corrupt, and the error says which group.
  Be bad = f;
  bad.b.replace(bad.b.find("sel") + 3, 4, std::string("\x00\x00\x00\x05", 4));
  EXPECT_NE(error_of([&] { read_bgeo_info(dir.write("bad.bgeo", bad.b)); }).find("point group 'sel' has 5 bits for 2"),
            std::string::npos);
}

TEST(Bgeo, TruncatedFilesGiveErrorsNamingTheFile) {
  TempDir dir;
  const std::string raw = io::gunzip(read_file(kRealFrame), "test");
  ASSERT_EQ(raw.size(), 1087016u);  // 102-byte header + 30192 * 36 + 00 FF
  for (size_t cut : {size_t(0), size_t(3), size_t(20), size_t(45), size_t(70), size_t(102), size_t(102 + 36 * 100 + 7),
                     raw.size() - 3, raw.size() - 1}) {
    const fs::path p = dir.write("cut_" + std::to_string(cut) + ".bgeo", raw.substr(0, cut));
    const std::string msg = error_of([&] { read_bgeo(p); });
    EXPECT_NE(msg.find(p.string()), std::string::npos) << cut << ": " << msg;
  }
  // Cutting the compressed stream instead.
  const std::string gz = read_file(kRealFrame);
  for (size_t cut : {size_t(1), size_t(10), gz.size() / 2, gz.size() - 4}) {
    const fs::path p = dir.write("gzcut_" + std::to_string(cut) + ".bgeo", gz.substr(0, cut));
    const std::string msg = error_of([&] { read_bgeo(p); });
    EXPECT_NE(msg.find(p.string()), std::string::npos) << cut << ": " << msg;
  }
  // Trailing garbage after the end marker.
  const fs::path extra = dir.write("extra.bgeo", raw + "xyz");
  EXPECT_NE(error_of([&] { read_bgeo(extra); }).find("after the end marker"), std::string::npos);
}

TEST(Bgeo, CorruptBytesGiveClearErrors) {
  TempDir dir;
  const std::string raw = io::gunzip(read_file(kRealFrame), "test");
  auto with = [&](size_t offset, std::string_view bytes) {
    std::string s = raw;
    s.replace(offset, bytes.size(), bytes);
    return s;
  };
  const fs::path magic = dir.write("magic.bgeo", with(0, "Bgeq"));
  EXPECT_NE(error_of([&] { read_bgeo(magic); }).find("not a BGEO file"), std::string::npos);
  const fs::path version = dir.write("version.bgeo", with(5, std::string("\0\0\0\4", 4)));
  EXPECT_NE(error_of([&] { read_bgeo(version); }).find("version 4"), std::string::npos);
  // The `id` attribute's type word is at 41 + 2 + 2 + 2 = 47.
  const fs::path type = dir.write("type.bgeo", with(47, std::string("\0\0\0\7", 4)));
  const std::string type_msg = error_of([&] { read_bgeo(type); });
  EXPECT_NE(type_msg.find("type 7"), std::string::npos) << type_msg;
  EXPECT_NE(type_msg.find(type.string()), std::string::npos);
  const fs::path as_float = dir.write("float_id.bgeo", with(47, std::string("\0\0\0\0", 4)));
  EXPECT_NE(error_of([&] { read_bgeo(as_float); }).find("attribute 'id' is float[1]"), std::string::npos);
  // A corrupt point count must fail on size, not allocate: 0x7fffffff points.
  const fs::path count = dir.write("count.bgeo", with(9, "\x7f\xff\xff\xff"));
  EXPECT_NE(error_of([&] { read_bgeo(count); }).find("truncated"), std::string::npos);
  const fs::path negative = dir.write("negative.bgeo", with(9, "\xff\xff\xff\xfe"));
  EXPECT_NE(error_of([&] { read_bgeo(negative); }).find("point count is -2"), std::string::npos);
  // Particle 0's id word is at 102 + 16: make it -3.
  const fs::path neg_id = dir.write("neg_id.bgeo", with(118, "\xff\xff\xff\xfd"));
  const std::string id_msg = error_of([&] { read_bgeo(neg_id); });
  EXPECT_NE(id_msg.find("particle 0 has id -3"), std::string::npos) << id_msg;
  // Particle 5's x = NaN.
  const fs::path nan = dir.write("nan.bgeo", with(102 + 36 * 5, "\x7f\xc0\x00\x00"));
  const std::string nan_msg = error_of([&] { read_bgeo(nan); });
  EXPECT_NE(nan_msg.find("particle 5"), std::string::npos) << nan_msg;
  EXPECT_NE(nan_msg.find("non-finite"), std::string::npos) << nan_msg;
  // Duplicate ids: give particle 1 the id of particle 0 (1277).
  const fs::path dup = dir.write("dup.bgeo", with(118 + 36, std::string("\0\0\x04\xfd", 4)));
  EXPECT_NE(error_of([&] { read_bgeo(dup); }).find("1277 occurs more than once"), std::string::npos);
}

// The classic reader refuses Houdini's JSON geometries, saying what they are and what spume does with them
// (the binary form is read as Houdini geometry through read_fluid_file, tested in io_houdini_test.cpp).
TEST(Bgeo, RefusesHoudiniJsonGeometrySayingWhatItIs) {
  TempDir dir;
  for (const std::string& bytes : {std::string("\x7fNSJb\x01\x02\x03", 8), std::string("[\"fileversion\",\"19.5\"]"),
                                   std::string("  {\"fileversion\":1}")}) {
    const fs::path p = dir.write("new.bgeo", bytes);
    const std::string msg = error_of([&] { read_bgeo(p); });
    EXPECT_NE(msg.find(bytes[0] == '\x7f' ? "read it as Houdini geometry" : "save it from Houdini as .bgeo or .bgeo.sc"),
              std::string::npos) << msg;
    EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
    const fs::path gz = dir.write("new_gz.bgeo", io::gzip_compress(bytes));
    EXPECT_NE(error_of([&] { read_bgeo(gz); }).find("JSON"), std::string::npos);
  }
}

TEST(Bgeo, RejectsUnusableVelocityAndMissingFile) {
  TempDir dir;
  Be f = header(1, 1);
  f.attr("v", 3, 1).f32(0).f32(0).f32(0).f32(1).i32(1).i32(2).i32(3).raw(std::string("\x00\xff", 2));
  const fs::path p = dir.write("intv.bgeo", f.b);
  EXPECT_NE(error_of([&] { read_bgeo(p); }).find("attribute 'v' is int[3]"), std::string::npos);
  const fs::path missing = dir.path / "missing.bgeo";
  EXPECT_EQ(error_of([&] { read_bgeo(missing); }), missing.string() + ": no such file");
  const fs::path not_diffuse = kRealFrame;
  EXPECT_NE(error_of([&] { read_bgeo_diffuse(not_diffuse); }).find("not a spume diffuse BGEO"), std::string::npos);
}

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "sim/core/error.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"
#include "tests/sim/io_test_support.h"
#include "sim/io/attribute_names.h"
#include "sim/io/ply.h"

namespace fs = std::filesystem;
using namespace spume;
using namespace spume::io_test;
using namespace spume::testing;

namespace {

}  // namespace

TEST(Ply, ReadsAsciiWithVelocityIdsAndAFaceElement) {
  TempDir dir;
  const fs::path p = dir.write("a.ply",
                               "ply\r\nformat ascii 1.0\ncomment made by hand\nelement vertex 3\n"
                               "property float x\nproperty float y\nproperty float z\nproperty uchar red\n"
                               "property float vx\nproperty float vy\nproperty float vz\nproperty int id\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0 255 1 0 0 10\n"
                               "1.5 -2 3e-2 0 0 1 0 11\n"
                               "+4 5 6 7 0 0 -1 12\n"
                               "3 0 1 2\n");
  std::vector<PointAttribute> attrs;
  const FluidFrame f = read_ply(p, &attrs);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f.positions[1], Vec3f(1.5f, -2, 0.03f));
  EXPECT_EQ(f.positions[2], Vec3f(4, 5, 6));
  EXPECT_EQ(f.velocities[0], Vec3f(1, 0, 0));
  EXPECT_EQ(f.velocities[2], Vec3f(0, 0, -1));
  EXPECT_EQ(f.ids, (std::vector<uint32_t>{10, 11, 12}));
  ASSERT_EQ(attrs.size(), 8u);
  EXPECT_EQ(attrs[3].name, "red");
  EXPECT_EQ(attrs[3].type, "uchar");
}

// Every name of the one attribute table (io/attribute_names.h), the velocity's spelt per component
// both ways PLY writers spell them: "vx" and "velocity_x". Written by hand, not by io::velocity_component.
TEST(Ply, ReadsEveryNameOfTheAttributeTable) {
  TempDir dir;
  const auto velocity = io::attribute_names(io::AttributeRole::Velocity), id = io::attribute_names(io::AttributeRole::Id),
             mass = io::attribute_names(io::AttributeRole::Mass);
  int file = 0;
  for (size_t k = 0; k < std::max({velocity.size(), id.size(), mass.size()}); ++k)
    for (const char* sep : {"", "_"}) {
      const std::string v(velocity[k % velocity.size()]);
      SCOPED_TRACE(v + sep + "x, " + std::string(id[k % id.size()]) + ", " + std::string(mass[k % mass.size()]));
      std::string text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
      for (const char* axis : {"x", "y", "z"}) text += "property float " + v + sep + axis + "\n";
      text += "property int " + std::string(id[k % id.size()]) + "\nproperty float " + std::string(mass[k % mass.size()]) +
              "\nend_header\n1 2 3 4 5 6 9 0.5\n";
      const FluidFrame f = read_ply(dir.write("k" + std::to_string(file++) + ".ply", text));
      ASSERT_EQ(f.size(), 1u);
      EXPECT_EQ(f.velocities, (std::vector<Vec3f>{Vec3f(4, 5, 6)}));
      EXPECT_EQ(f.ids, (std::vector<uint32_t>{9}));
      EXPECT_EQ(f.masses, (std::vector<float>{0.5f}));
    }
}

TEST(Ply, ReadsBigEndianWithListsBeforeAndInsideVertices) {
  TempDir dir;
  std::string s =
      "ply\nformat binary_big_endian 1.0\nelement material 2\nproperty list uchar float coeffs\n"
      "element vertex 2\nproperty double x\nproperty double y\nproperty double z\n"
      "property list ushort uint neighbours\nproperty float velocity_x\nproperty float velocity_y\n"
      "property float velocity_z\nproperty uint id\nend_header\n";
  // material 0: 2 floats, material 1: none
  s += char(2);
  be(s, 1.0f);
  be(s, 2.0f);
  s += char(0);
  // vertex 0: neighbours [1], v = (0.5, 0, 0), id 7; vertex 1: neighbours [], id 8
  be(s, 0.1);
  be(s, 0.2);
  be(s, 0.3);
  be(s, uint16_t(1));
  be(s, uint32_t(1));
  be(s, 0.5f);
  be(s, 0.0f);
  be(s, 0.0f);
  be(s, uint32_t(7));
  be(s, -1.0);
  be(s, 10.0);
  be(s, 1e-3);
  be(s, uint16_t(0));
  be(s, 0.0f);
  be(s, -9.81f);
  be(s, 0.0f);
  be(s, uint32_t(8));
  const fs::path p = dir.write("b.ply", s);
  const FluidFrame f = read_ply(p);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f.positions[0], Vec3f(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(f.positions[1], Vec3f(-1, 10, 1e-3f));
  EXPECT_EQ(f.velocities[0], Vec3f(0.5f, 0, 0));
  EXPECT_EQ(f.velocities[1], Vec3f(0, -9.81f, 0));
  EXPECT_EQ(f.ids, (std::vector<uint32_t>{7, 8}));
}

TEST(Ply, BinaryRoundTrip) {
  TempDir dir;
  FluidFrame f;
  f.index = 4;
  f.positions = {Vec3f(1, 2, 3), Vec3f(-4, 5.5f, 1e-7f)};
  f.velocities = {Vec3f(0, 0, 1), Vec3f(2, 2, 2)};
  f.ids = {4294967295u, 0};
  f.masses = {1.0f, 2.0f};
  const fs::path p = dir.path / "r.ply";
  write_ply(p, f);
  const std::string bytes = read_file(p);
  const size_t body = bytes.find("end_header\n") + 11;
  EXPECT_NE(bytes.find("format binary_little_endian 1.0\n"), std::string::npos);
  EXPECT_NE(bytes.find("element vertex 2\n"), std::string::npos);
  EXPECT_EQ(bytes.size() - body, 2u * (12 + 12 + 4 + 4));
  float y1;
  std::memcpy(&y1, bytes.data() + body + 32 + 4, 4);  // second vertex's y
  EXPECT_EQ(y1, 5.5f);
  const FluidFrame g = read_ply(p);
  EXPECT_EQ(g.positions, f.positions);
  EXPECT_EQ(g.velocities, f.velocities);
  EXPECT_EQ(g.ids, f.ids);
  EXPECT_EQ(g.masses, f.masses);
  write_ply(p, FluidFrame{});
  EXPECT_EQ(read_ply(p).size(), 0u);
}

TEST(Ply, CorruptAndTruncatedFilesGiveErrors) {
  TempDir dir;
  FluidFrame f;
  f.positions = {Vec3f(1, 2, 3), Vec3f(4, 5, 6), Vec3f(7, 8, 9)};
  f.ids = {1, 2, 3};
  const fs::path good = dir.path / "good.ply";
  write_ply(good, f);
  const std::string bytes = read_file(good);
  const size_t body = bytes.find("end_header\n") + 11;
  for (size_t cut : {size_t(2), size_t(20), body - 3, body + 5, bytes.size() - 1}) {
    const fs::path p = dir.write("cut" + std::to_string(cut) + ".ply", bytes.substr(0, cut));
    const std::string msg = error_of([&] { read_ply(p); });
    EXPECT_NE(msg.find(p.string()), std::string::npos) << cut << ": " << msg;
  }
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n";
  auto msg = [&](const std::string& name, const std::string& text) {
    const fs::path p = dir.write(name, text);
    return error_of([&] { read_ply(p); });
  };
  EXPECT_NE(msg("noz.ply", header + "end_header\n0 0\n1 1\n").find("lacks scalar properties x, y and z"), std::string::npos);
  EXPECT_NE(msg("fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n").find("binary_middle_endian"), std::string::npos);
  EXPECT_NE(msg("type.ply", header + "property half z\nend_header\n").find("unknown PLY property type 'half'"), std::string::npos);
  EXPECT_NE(msg("word.ply", header + "property float z\nend_header\n0 0 zero\n").find("found 'zero'"), std::string::npos);
  EXPECT_NE(msg("short.ply", header + "property float z\nend_header\n0 0 0\n1 1\n").find("truncated"), std::string::npos);
  EXPECT_NE(msg("nan.ply", header + "property float z\nend_header\n0 0 0\n1 nan 1\n").find("particle 1"), std::string::npos);
  EXPECT_NE(msg("id.ply", header + "property float z\nproperty float id\nend_header\n0 0 0 1.5\n1 1 1 2\n").find("id 1.5"),
            std::string::npos);
  EXPECT_NE(msg("nothing.ply", "solid x\n").find("not a PLY file"), std::string::npos);
  EXPECT_NE(msg("novertex.ply", "ply\nformat ascii 1.0\nelement face 0\nend_header\n").find("no 'vertex' element"),
            std::string::npos);
  // A corrupt count fails on size rather than allocating.
  EXPECT_NE(msg("huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 99999999999999\nproperty float x\n"
                            "property float y\nproperty float z\nend_header\n0123456789ab")
                .find("claims 99999999999999 rows"),
            std::string::npos);
}

// The OpenVDB points writer (io/vdb_points_writer.h), read back with OpenVDB's own API: every
// attribute within the error the header states, computed here from the codecs' definitions (16-bit
// fixed point across a voxel, rounded; half floats with 11 significant bits), and the bytes the same
// for any thread count and from run to run.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include <openvdb/openvdb.h>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/points/PointGroup.h>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/io/vdb_points_writer.h"
#include "tests/support/error_of.h"
#include "tests/support/temp_dir.h"

using namespace spume;
using namespace spume::testing;
namespace vp = openvdb::points;

namespace {

struct ReadPoint {
  openvdb::Vec3d position;
  openvdb::Vec3f velocity;
  float lifetime = 0.0f;
  int32_t type = -1;
  std::array<bool, 3> groups{};
};

// Every point of the grid "points" by id, positions in world space (double).
std::map<int64_t, ReadPoint> read_points(const std::string& bytes, openvdb::MetaMap* grid_meta = nullptr) {
  openvdb::initialize();
  std::istringstream in(bytes, std::ios::binary);
  openvdb::io::Stream stream(in, /*delayLoad=*/false);
  const openvdb::GridPtrVecPtr grids = stream.getGrids();
  EXPECT_EQ(grids->size(), 1u);
  const auto grid = openvdb::gridPtrCast<vp::PointDataGrid>(grids->front());
  EXPECT_TRUE(grid);
  EXPECT_EQ(grid->getName(), "points");
  if (grid_meta) *grid_meta = *grid;
  std::map<int64_t, ReadPoint> points;
  for (auto leaf = grid->tree().cbeginLeaf(); leaf; ++leaf) {
    const vp::AttributeSet::Descriptor& d = leaf->attributeSet().descriptor();
    EXPECT_EQ(d.valueType(d.find("P")), "vec3s");
    vp::AttributeHandle<openvdb::Vec3f> p(leaf->constAttributeArray("P"));
    vp::AttributeHandle<openvdb::Vec3f> v(leaf->constAttributeArray("v"));
    vp::AttributeHandle<float> life(leaf->constAttributeArray("lifetime"));
    vp::AttributeHandle<int64_t> id(leaf->constAttributeArray("id"));
    vp::AttributeHandle<int32_t> type(leaf->constAttributeArray("type"));
    const vp::GroupHandle spray = leaf->groupHandle("spray"), foam = leaf->groupHandle("foam"),
                          bubble = leaf->groupHandle("bubble");
    for (auto voxel = leaf->beginIndexOn(); voxel; ++voxel) {
      ReadPoint r;
      const openvdb::Vec3d index_space = voxel.getCoord().asVec3d() + openvdb::Vec3d(p.get(*voxel));
      r.position = grid->transform().indexToWorld(index_space);
      r.velocity = v.get(*voxel);
      r.lifetime = life.get(*voxel);
      r.type = type.get(*voxel);
      r.groups = {spray.get(*voxel), foam.get(*voxel), bubble.get(*voxel)};
      EXPECT_TRUE(points.emplace(id.get(*voxel), r).second) << "id " << id.get(*voxel) << " twice";
    }
  }
  return points;
}

// A known set: particles scattered over several leaves on both sides of the origin, some exactly on
// voxel faces, speeds from below half's normal range to 1000 m/s, ids with every field in use.
DiffuseFrame known_frame(size_t n, float voxel) {
  DiffuseFrame frame;
  frame.index = 17;
  frame.time = 0.34;
  frame.resize(n);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> pos(-3.0f, 3.0f), unit(-1.0f, 1.0f), life(0.0f, 4.0f);
  for (size_t i = 0; i < n; ++i) {
    frame.positions[i] = Vec3f(pos(rng), pos(rng) * 0.1f + 1.5f, pos(rng));
    if (i % 50 == 0) frame.positions[i] = Vec3f(float(int(i % 7) - 3) * voxel, 0.5f * voxel, 3.5f * voxel);
    const float scale = i % 3 == 0 ? 1e-6f : (i % 3 == 1 ? 3.0f : 1000.0f);
    frame.velocities[i] = Vec3f(unit(rng), unit(rng), unit(rng)) * scale;
    frame.lifetimes[i] = life(rng);
    frame.types[i] = DiffuseType(i % 3);
    frame.ids[i] = diffuse_id(uint32_t(0xFFFFFFF0u + i % 16), uint32_t(i * 977 % (kMaxBirthStep + 1)), uint32_t(i % 4096));
  }
  return frame;
}

}  // namespace

TEST(VdbPointsWriter, ReadBackWithinTheStatedQuantisation) {
  const float r = 0.02f, voxel = 2.0f * r;
  ASSERT_EQ(vdb_points_voxel_size(r), voxel);
  const DiffuseFrame frame = known_frame(3000, voxel);
  const std::map<int64_t, ReadPoint> points = read_points(vdb_points_bytes(frame, voxel));
  ASSERT_EQ(points.size(), frame.size());
  const double step = double(voxel) / 65535.0;  // 16 bits across a voxel
  double worst_steps = 0.0;
  for (size_t i = 0; i < frame.size(); ++i) {
    const auto found = points.find(int64_t(frame.ids[i]));
    ASSERT_NE(found, points.end()) << "id " << frame.ids[i];
    const ReadPoint& got = found->second;
    for (int a = 0; a < 3; ++a) {
      const double x = frame.positions[i][a];
      // Rounded to the nearest step, read back in double: half a step and a little float slack (the
      // codec scales a float offset); a reader converting to float adds half an ulp of x.
      const double err = std::fabs(got.position[a] - x);
      EXPECT_LE(err, 0.52 * step) << "particle " << i << " axis " << a << " at " << x;
      EXPECT_LE(err, vdb_position_error(voxel, float(x)));
      worst_steps = std::max(worst_steps, err / step);
      const double v = frame.velocities[i][a];
      EXPECT_LE(std::fabs(double(got.velocity[a]) - v), std::max(std::fabs(v) / 2048.0, std::ldexp(1.0, -25)))
          << "particle " << i << " v" << a << " " << v;
      EXPECT_LE(std::fabs(double(got.velocity[a]) - v), vdb_velocity_error(float(v)));
    }
    EXPECT_EQ(got.lifetime, frame.lifetimes[i]);
    EXPECT_EQ(got.type, int32_t(frame.types[i]));
    for (int t = 0; t < 3; ++t) EXPECT_EQ(got.groups[t], t == int(frame.types[i])) << "group " << t << " of " << i;
  }
  // 16 bits across the voxel, not finer: some particle is off by nearly half a step.
  EXPECT_GT(worst_steps, 0.45);
}

TEST(VdbPointsWriter, FrameAndTimeAsGridMetadata) {
  const DiffuseFrame frame = known_frame(10, 0.04f);
  openvdb::MetaMap meta;
  read_points(vdb_points_bytes(frame, 0.04f), &meta);
  EXPECT_EQ(meta.metaValue<int32_t>("frame"), 17);
  EXPECT_EQ(meta.metaValue<double>("time"), 0.34);
}

TEST(VdbPointsWriter, EmptyFrameIsAValidFileWithNoPoints) {
  DiffuseFrame empty;
  EXPECT_TRUE(read_points(vdb_points_bytes(empty, 0.04f)).empty());
}

TEST(VdbPointsWriter, SameBytesForAnyThreadCountAndEveryRun) {
  const DiffuseFrame frame = known_frame(20000, 0.04f);
  set_thread_count(1);
  const std::string one = vdb_points_bytes(frame, 0.04f);
  set_thread_count(2);
  const std::string two = vdb_points_bytes(frame, 0.04f);
  const std::string again = vdb_points_bytes(frame, 0.04f);
  set_thread_count(0);
  EXPECT_TRUE(one == two) << "1 and 2 threads differ";
  EXPECT_TRUE(two == again) << "two runs differ";
  // OpenVDB's random file UUID is replaced by a digest of the content: other points, another UUID.
  DiffuseFrame moved = frame;
  moved.positions[0].x() += 0.01f;
  const std::string other = vdb_points_bytes(moved, 0.04f);
  EXPECT_NE(one.substr(21, 36), other.substr(21, 36));
}

TEST(VdbPointsWriter, WrittenAtomicallyAndReadableAsAFile) {
  TempDir dir;
  const DiffuseFrame frame = known_frame(100, 0.04f);
  const auto path = dir / "out" / "diffuse_0017.vdb";
  write_vdb_points(path, frame, 0.04f);
  size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir / "out")) ++files;
  EXPECT_EQ(files, 1u) << "a temporary file was left";
  openvdb::io::File file(path.string());
  file.open();
  const auto grid = openvdb::gridPtrCast<vp::PointDataGrid>(file.readGrid("points"));
  ASSERT_TRUE(grid);
  EXPECT_EQ(vp::pointCount(grid->tree()), 100u);
  EXPECT_TRUE(file.compression() & openvdb::io::COMPRESS_BLOSC);
}

TEST(VdbPointsWriter, VelocityBeyondHalfRangeIsAnErrorNamingTheParticle) {
  DiffuseFrame frame = known_frame(4, 0.04f);
  frame.velocities[2].y() = 70000.0f;
  const std::string message = error_of([&] { write_vdb_points("/nonexistent/x.vdb", frame, 0.04f); });
  EXPECT_NE(message.find("/nonexistent/x.vdb"), std::string::npos) << message;
  EXPECT_NE(message.find(std::to_string(frame.ids[2])), std::string::npos) << message;
  EXPECT_NE(message.find("65504"), std::string::npos) << message;
}

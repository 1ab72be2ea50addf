// Fog volumes (sim/io/fog_volumes.h): each sphere's volume is spread over voxels without loss, read
// back with OpenVDB's own API; expectations are closed forms (sphere volumes, trilinear weights).
#include <gtest/gtest.h>

#include <cmath>

#include <openvdb/openvdb.h>
#include <openvdb/io/Stream.h>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/io/fog_volumes.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

double sphere_volume(double r) { return 4.0 / 3.0 * M_PI * r * r * r; }

openvdb::GridPtrVecPtr read_grids(const std::string& bytes) {
  openvdb::initialize();
  std::istringstream in(bytes, std::ios::binary);
  openvdb::io::Stream stream(in);
  return stream.getGrids();
}

openvdb::GridBase::Ptr grid_named(const openvdb::GridPtrVecPtr& grids, const std::string& name) {
  for (const auto& g : *grids)
    if (g->getName() == name) return g;
  return nullptr;
}

// Sum of a float grid's values times the voxel volume: the volume it holds, m^3.
double integral(const openvdb::GridBase::Ptr& base) {
  const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  EXPECT_TRUE(grid);
  if (!grid) return 0.0;
  const double v = grid->voxelSize()[0];
  double sum = 0.0;
  for (auto it = grid->cbeginValueOn(); it; ++it) sum += double(*it) * double(it.getVoxelCount());
  return sum * v * v * v;
}

DiffuseFrame particles(std::initializer_list<std::tuple<Vec3f, Vec3f, DiffuseType>> list) {
  DiffuseFrame f;
  f.index = 3, f.time = 0.1;
  uint32_t id = 0;
  for (const auto& [p, v, t] : list) {
    f.positions.push_back(p), f.velocities.push_back(v), f.types.push_back(t);
    f.lifetimes.push_back(1.0f), f.ids.push_back(id++);
  }
  return f;
}

TEST(FogVolumes, ASmallSphereSpreadsTrilinearlyOverTheEightVoxelsAroundIt) {
  // Voxel 1/8 m; centre at (0.15625, 0.25, -0.0625): index coordinates (1.25, 2, -0.5), all exact.
  const auto w = sphere_voxel_weights(Vec3f(0.15625f, 0.25f, -0.0625f), 0.05f, 0.125f);
  double sum = 0.0, cx = 0.0, cz = 0.0;
  for (const VoxelWeight& v : w) {
    sum += v.weight, cx += v.weight * v.ijk[0], cz += v.weight * v.ijk[2];
    EXPECT_EQ(v.ijk[1], 2) << "y lies on a voxel centre: no share beside it";
  }
  EXPECT_EQ(w.size(), 4u);
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_NEAR(cx, 1.25, 1e-6);   // the centroid is kept
  EXPECT_NEAR(cz, -0.5, 1e-6);
  for (const VoxelWeight& v : w)  // (0.75 or 0.25) x 0.5
    EXPECT_NEAR(v.weight, (v.ijk[0] == 1 ? 0.75 : 0.25) * 0.5, 1e-6);
}

TEST(FogVolumes, ALargeSphereCoversTheVoxelsInsideItSymmetrically) {
  // Radius 3 voxels, centred on a voxel centre: the weights sum to one, the voxels well inside share
  // equally, none lies beyond r + 1/2, and the centroid is the centre.
  const float voxel = 0.125f;  // and the centre at index (5, 5, 5): exact
  const auto w = sphere_voxel_weights(Vec3f(0.625f, 0.625f, 0.625f), 3 * voxel, voxel);
  double sum = 0.0, c[3] = {0, 0, 0}, inner = -1.0;
  for (const VoxelWeight& v : w) {
    sum += v.weight;
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) c[a] += v.weight * v.ijk[size_t(a)], d2 += (v.ijk[size_t(a)] - 5.0) * (v.ijk[size_t(a)] - 5.0);
    EXPECT_LT(std::sqrt(d2), 3.5 + 1e-9);
    if (d2 <= 2.0 * 2.0) {
      if (inner < 0.0) inner = v.weight;
      EXPECT_NEAR(v.weight, inner, 1e-12);
    }
  }
  EXPECT_NEAR(sum, 1.0, 1e-12);
  for (double x : c) EXPECT_NEAR(x, 5.0, 1e-9);
  // About the sphere's volume in voxels (4/3 pi 27 = 113): the ramp counts rim voxels by how far in
  // their centres lie, a lattice count off by a few percent.
  EXPECT_NEAR(1.0 / inner, sphere_volume(3.0), 0.05 * sphere_volume(3.0));
}

TEST(FogVolumes, EachTypeGridHoldsItsParticlesVolumeAndDensityTheirSum) {
  FogLook look;
  look.voxel = 0.02f;
  look.radius = {0.004f, 0.05f, 0.01f};  // spray below a voxel, foam over several, bubbles half a voxel
  look.alpha = 80.0f;
  const DiffuseFrame frame = particles({
      {Vec3f(0.013f, 0.5f, 0.2f), Vec3f(1, 0, 0), DiffuseType::Spray},
      {Vec3f(0.3f, 0.51f, 0.2f), Vec3f(0, 2, 0), DiffuseType::Spray},
      {Vec3f(-0.2f, 0.1f, 0.05f), Vec3f(0, 0, 0), DiffuseType::Foam},
      {Vec3f(-0.21f, 0.1f, 0.07f), Vec3f(0, 0, 0), DiffuseType::Foam},
      {Vec3f(0.5f, -0.3f, 0.0f), Vec3f(0, 0, -1), DiffuseType::Bubble},
  });
  const auto grids = read_grids(fog_volume_bytes(frame, look));
  ASSERT_EQ(grids->size(), 5u);
  EXPECT_NEAR(integral(grid_named(grids, "spray")), 2 * sphere_volume(0.004), 1e-4 * 2 * sphere_volume(0.004));
  EXPECT_NEAR(integral(grid_named(grids, "foam")), 2 * sphere_volume(0.05), 1e-4 * 2 * sphere_volume(0.05));
  EXPECT_NEAR(integral(grid_named(grids, "bubble")), sphere_volume(0.01), 1e-4 * sphere_volume(0.01));
  const double all = 2 * sphere_volume(0.004) + 2 * sphere_volume(0.05) + sphere_volume(0.01);
  EXPECT_NEAR(integral(grid_named(grids, "density")), all, 1e-4 * all);
  const auto spray = grid_named(grids, "spray");
  EXPECT_EQ(spray->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_FLOAT_EQ(spray->metaValue<float>("alpha"), 80.0f);
  EXPECT_FLOAT_EQ(spray->metaValue<float>("radius"), 0.004f);
  EXPECT_EQ(spray->metaValue<int32_t>("frame"), 3);
  EXPECT_NEAR(spray->voxelSize()[0], 0.02, 1e-9);

  // Velocity: each particle alone in its voxels carries its own; none where nothing is.
  const auto v = openvdb::gridPtrCast<openvdb::Vec3SGrid>(grid_named(grids, "v"));
  ASSERT_TRUE(v);
  const openvdb::Vec3s first = v->tree().getValue(openvdb::Coord(1, 25, 10));  // voxel centre (0.02, 0.5, 0.2)
  EXPECT_NEAR(first.x(), 1.0f, 1e-6f);
  EXPECT_NEAR(first.y(), 0.0f, 1e-6f);
  const openvdb::Vec3s bubble = v->tree().getValue(openvdb::Coord(25, -15, 0));
  EXPECT_NEAR(bubble.z(), -1.0f, 1e-6f);
  EXPECT_FALSE(v->tree().isValueOn(openvdb::Coord(100, 100, 100)));
}

TEST(FogVolumes, WhereTwoParticlesShareAVoxelTheVelocityIsTheirVolumeWeightedMean) {
  FogLook look;
  look.voxel = 0.1f;
  look.radius = {0.02f, 0.04f, 0.0f};  // foam has 8 times spray's volume
  // Both exactly on the centre of voxel (1, 1, 1): all of each lands there.
  const DiffuseFrame frame = particles({{Vec3f(0.1f, 0.1f, 0.1f), Vec3f(9, 0, 0), DiffuseType::Spray},
                                        {Vec3f(0.1f, 0.1f, 0.1f), Vec3f(0, 0, 0), DiffuseType::Foam}});
  const auto grids = read_grids(fog_volume_bytes(frame, look));
  EXPECT_EQ(grid_named(grids, "bubble"), nullptr) << "a type not drawn has no grid";
  const auto v = openvdb::gridPtrCast<openvdb::Vec3SGrid>(grid_named(grids, "v"));
  ASSERT_TRUE(v);
  EXPECT_NEAR(v->tree().getValue(openvdb::Coord(1, 1, 1)).x(), 9.0f * 1.0f / 9.0f, 1e-5f);  // 9 x 1 / (1 + 8)
}

TEST(FogVolumes, TheBytesDependOnlyOnTheFrameAndTheLook) {
  FogLook look;
  look.voxel = 0.05f;
  look.radius = {0.01f, 0.02f, 0.03f};
  const DiffuseFrame frame = particles({{Vec3f(0.1f, 0.2f, 0.3f), Vec3f(1, 2, 3), DiffuseType::Foam}});
  EXPECT_EQ(fog_volume_bytes(frame, look), fog_volume_bytes(frame, look));
  FogLook other = look;
  other.radius[1] = 0.021f;
  EXPECT_NE(fog_volume_bytes(frame, look), fog_volume_bytes(frame, other));
  EXPECT_NE(fog_volumes_format(look), fog_volumes_format(other));
}

// Over 2^20 particles the splat runs in chunks, in parallel: the same bytes for 1 and 2 threads, and
// still each type's volume.
TEST(FogVolumes, AFrameOfManyChunksGivesTheSameBytesForOneAndTwoThreads) {
  DiffuseFrame frame;
  const size_t n = 1'200'000;  // two chunks
  frame.resize(n);
  uint64_t state = 12345;
  auto unit = [&] {  // splitmix64 to [0, 1)
    uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  for (size_t i = 0; i < n; ++i) {
    const float x = float(unit()), y = float(unit()), z = float(unit());
    frame.positions[i] = Vec3f(x, 0.2f * y, z);
    frame.velocities[i] = Vec3f(1.0f - 2.0f * z, 0.5f, 0.0f);
    frame.types[i] = DiffuseType(i % 3), frame.lifetimes[i] = 1.0f, frame.ids[i] = i;
  }
  FogLook look;
  look.voxel = 0.02f;
  look.radius = {0.005f, 0.015f, 0.01f};  // below the voxel: 8 voxels each, a fast test
  set_thread_count(1);
  const std::string one = fog_volume_bytes(frame, look);
  set_thread_count(2);
  const std::string two = fog_volume_bytes(frame, look);
  set_thread_count(0);
  EXPECT_TRUE(one == two) << "the bytes depend on the thread count";
  const auto grids = read_grids(two);
  const double foam = double(n / 3) * sphere_volume(0.015);
  EXPECT_NEAR(integral(grid_named(grids, "foam")), foam, 1e-4 * foam);
}

TEST(FogVolumes, UnusableLooksAreErrorsNamingWhatIsWrong) {
  const DiffuseFrame frame = particles({{Vec3f(0, 0, 0), Vec3f(0, 0, 0), DiffuseType::Spray}});
  auto message = [&](const FogLook& look) {
    try {
      fog_volume_bytes(frame, look);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  FogLook look;
  look.radius = {0.01f, 0.01f, 0.01f};
  EXPECT_NE(message(look).find("voxel size 0 m is not a positive number"), std::string::npos) << message(look);
  look.voxel = 0.01f;
  look.radius = {0, 0, 0};
  EXPECT_NE(message(look).find("no diffuse type is drawn"), std::string::npos) << message(look);
  look.radius = {1.0f, 0, 0};
  EXPECT_NE(message(look).find("at most 64 are allowed"), std::string::npos) << message(look);
  // 30,000 spheres of 60 voxels' radius, about a million voxels each: over the bound, said with figures.
  DiffuseFrame many;
  many.resize(30'000);
  for (size_t i = 0; i < many.size(); ++i) many.types[i] = DiffuseType::Foam, many.ids[i] = i, many.lifetimes[i] = 1;
  look.voxel = 0.001f;
  look.radius = {0.0f, 0.06f, 0.0f};
  try {
    fog_volume_bytes(many, look);
    ADD_FAILURE() << "a voxel far too small was not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("choose a larger voxel (output.fog)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace spume

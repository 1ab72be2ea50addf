#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "sim/core/error.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"
#include "sim/io/bgeo.h"
#include "sim/io/particle_file.h"
#include "sim/io/ply.h"
#include "sim/io/spume_cache.h"
#include "sim/io/vtk.h"
#include "tests/support/text.h"

namespace fs = std::filesystem;
using namespace spume;
using namespace spume::testing;

namespace {

const fs::path kRealFrame = fs::path(SPUME_TEST_DATA_DIR) / "splishsplash_rest_30192.bgeo";

FluidFrame sample() {
  FluidFrame f;
  f.positions = {Vec3f(0, 0, 0), Vec3f(1, 2, 3), Vec3f(-1, -2, 0.5f)};
  f.velocities = {Vec3f(0, 0, 1), Vec3f(0, 1, 0), Vec3f(1, 0, 0)};
  f.ids = {2, 1, 0};
  return f;
}

using spume::testing::contains;

}  // namespace

TEST(IoParticleFile, DispatchesOnExtension) {
  TempDir dir;
  const FluidFrame f = sample();
  write_bgeo(dir.path / "a.bgeo", f);
  write_bgeo(dir.path / "a.bgeo.gz", f);
  write_bgeo(dir.path / "a.BHCLASSIC", f);
  write_vtk(dir.path / "a.vtk", f);
  write_ply(dir.path / "a.ply", f);
  write_fluid_cache(dir.path / "a.spf", f, 0.02f);
  std::ofstream(dir.path / "a.vtu") << "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPoints=\"3\">"
                                       "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
                                       "0 0 0 1 2 3 -1 -2 0.5</DataArray></Points><PointData>"
                                       "<DataArray type=\"Float32\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"ascii\">"
                                       "0 0 1 0 1 0 1 0 0</DataArray><DataArray type=\"Int32\" Name=\"id\" format=\"ascii\">"
                                       "2 1 0</DataArray></PointData></Piece></UnstructuredGrid></VTKFile>";
  for (const char* name : {"a.bgeo", "a.bgeo.gz", "a.BHCLASSIC", "a.vtk", "a.ply", "a.spf", "a.vtu"}) {
    const FluidFrame g = read_fluid_file(dir.path / name);
    EXPECT_EQ(g.positions, f.positions) << name;
    EXPECT_EQ(g.velocities, f.velocities) << name;
    EXPECT_EQ(g.ids, f.ids) << name;
  }
  EXPECT_EQ(particle_format("x/y.vtp"), ParticleFormat::VtkXml);
  EXPECT_EQ(particle_format("y.SPD"), ParticleFormat::DiffuseCache);
}

TEST(IoParticleFile, ErrorsForUnknownExtensionMissingFileAndDiffuseCache) {
  TempDir dir;
  std::ofstream(dir.path / "a.xyz") << "1 2 3\n";
  const std::string unknown = error_of([&] { read_fluid_file(dir.path / "a.xyz"); });
  EXPECT_TRUE(contains(unknown, "unknown particle file extension '.xyz'")) << unknown;
  EXPECT_TRUE(contains(unknown, ".bgeo, .bgeo.gz")) << unknown;
  const fs::path missing = dir.path / "missing.bgeo";
  EXPECT_EQ(error_of([&] { read_fluid_file(missing); }), missing.string() + ": no such file");
  EXPECT_EQ(error_of([&] { describe_particle_file(missing); }), missing.string() + ": no such file");
  DiffuseFrame d;
  write_diffuse_cache(dir.path / "d.spd", d);
  EXPECT_TRUE(contains(error_of([&] { read_fluid_file(dir.path / "d.spd"); }), "not a fluid frame"));
}

// .bgeo.sc (any case) and Houdini's binary JSON under any name are Houdini geometry; when broken, reading
// them names the file and what is wrong (the real files are read in io_houdini_test.cpp).
TEST(IoParticleFile, HoudiniGeometryIsRecognisedAndBrokenFilesNamed) {
  TempDir dir;
  const fs::path sc = dir.write("f_1.bgeo.sc", "blosc blocks");
  const fs::path upper = dir.write("F_2.BGEO.SC", "blosc blocks");
  const fs::path json = dir.write("f_3.hjson", std::string("\x7fNSJb[", 6));  // binary JSON, any name
  for (const fs::path& p : {sc, upper, json}) {
    EXPECT_EQ(particle_format(p), ParticleFormat::HoudiniGeometry) << p;
    const std::string msg = error_of([&] { describe_particle_file(p); });
    EXPECT_TRUE(contains(msg, p.string() + ": ")) << msg;
    EXPECT_TRUE(contains(msg, p == json ? "truncated" : "it must start with 'scf1'")) << msg;
  }
  // Other unknown files keep the list of extensions.
  const fs::path other = dir.write("f.xyz", "1 2 3");
  EXPECT_TRUE(contains(error_of([&] { particle_format(other); }), "allowed .bgeo, .bgeo.gz, .bgeo.sc")) << other;
}

TEST(IoParticleFile, EmptyFramesAreReadAndNonFinitePositionsRejected) {
  TempDir dir;
  std::ofstream(dir.path / "empty.ply") << "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                                           "property float z\nend_header\n";
  EXPECT_EQ(read_fluid_file(dir.path / "empty.ply").size(), 0u);
  std::ofstream(dir.path / "nan.vtk") << "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n"
                                         "0 0 0 1 1 1 2 -inf 2\n";
  const std::string msg = error_of([&] { read_fluid_file(dir.path / "nan.vtk"); });
  EXPECT_TRUE(contains(msg, (dir.path / "nan.vtk").string())) << msg;
  EXPECT_TRUE(contains(msg, "particle 2")) << msg;
}

TEST(IoParticleFile, DescribesTheRealFrame) {
  const std::string d = describe_particle_file(kRealFrame);
  EXPECT_TRUE(contains(d, "classic BGEO version 5, gzip-compressed")) << d;
  EXPECT_TRUE(contains(d, "points: 30192")) << d;
  EXPECT_TRUE(contains(d, "id (int, 1), velocity (vector, 3), density (float, 1)")) << d;
  EXPECT_TRUE(contains(d, "ids: 0 .. 30191")) << d;
  // Bounds from the Python decode in io_bgeo_test.cpp (min (-1.91000009, 0.08999019, -0.65999997), max
  // (-0.99000013, 1.52999020, 0.66000003)), printed to 0.1 mm without trailing zeros.
  EXPECT_TRUE(contains(d, "bounds: (-1.91, 0.09, -0.66) .. (-0.99, 1.53, 0.66)")) << d;
}

TEST(IoParticleFile, DescribesDiffuseCachesAndFluidCaches) {
  TempDir dir;
  DiffuseFrame d;
  d.index = 9;
  d.ids = {diffuse_id(1, 0, 0), diffuse_id(2, 0, 0), diffuse_id(3, 0, 0), diffuse_id(3, 0, 1)};
  d.positions = {Vec3f(0, 0, 0), Vec3f(1, 1, 1), Vec3f(2, 0, 0), Vec3f(0, 3, 0)};
  d.velocities.assign(4, Vec3f(0, 0, 0));
  d.lifetimes = {0.5f, 2.0f, 1.25f, 3.5f};
  d.types = {DiffuseType::Foam, DiffuseType::Spray, DiffuseType::Foam, DiffuseType::Bubble};
  write_diffuse_cache(dir.path / "d.spd", d);
  const std::string text = describe_particle_file(dir.path / "d.spd");
  EXPECT_TRUE(contains(text, "spume diffuse cache")) << text;
  EXPECT_TRUE(contains(text, "particles: 4 (spray 1, foam 2, bubble 1)")) << text;
  EXPECT_TRUE(contains(text, "lifetime: 0.5 .. 3.5 s")) << text;
  EXPECT_TRUE(contains(text, "frame: 9")) << text;

  write_bgeo(dir.path / "d.bgeo", d);
  const std::string bgeo = describe_particle_file(dir.path / "d.bgeo");
  EXPECT_TRUE(contains(bgeo, "spume diffuse particles")) << bgeo;
  EXPECT_TRUE(contains(bgeo, "(spray 1, foam 2, bubble 1)")) << bgeo;

  write_fluid_cache(dir.path / "f.spf", sample(), 0.025f);
  const std::string fluid = describe_particle_file(dir.path / "f.spf");
  EXPECT_TRUE(contains(fluid, "particle radius 0.025 m")) << fluid;
  EXPECT_TRUE(contains(fluid, "points: 3")) << fluid;
  EXPECT_TRUE(contains(fluid, "bounds: (-1, -2, 0) .. (1, 2, 3)")) << fluid;
}

// Bounds resolve 0.1 mm however far from the origin (6 significant digits would print 10 km as 10000,
// 10 cm), and 1e-3 of the extent for smaller fluids (a 1 cm drop to 10 micrometres).
TEST(IoParticleFile, BoundsKeepMillimetresFarOutAndScaleDownForSmallFluids) {
  TempDir dir;
  FluidFrame far;
  // Floats near 1e4 are 2^-10 m apart: 10000 + 5 / 1024 = 10000.0048828125 is exact, as are the others.
  far.positions = {Vec3f(10000.0f + 5.0f / 1024, 0.5f, -10000.0f - 5.0f / 1024),
                   Vec3f(10001.0f + 5.0f / 1024, 0.75f, -9999.5f)};
  write_ply(dir.path / "far.ply", far);
  const std::string text = describe_particle_file(dir.path / "far.ply");
  EXPECT_TRUE(contains(text, "bounds: (10000.0049, 0.5, -10000.0049) .. (10001.0049, 0.75, -9999.5)")) << text;

  FluidFrame drop;  // 1 cm across: 5 decimals
  drop.positions = {Vec3f(0.0012346f, 0.002f, 0.003f), Vec3f(0.0112346f, 0.0045f, 0.005f)};
  write_ply(dir.path / "drop.ply", drop);
  const std::string small = describe_particle_file(dir.path / "drop.ply");
  EXPECT_TRUE(contains(small, "bounds: (0.00123, 0.002, 0.003) .. (0.01123, 0.0045, 0.005)")) << small;
}

// llvmpipe thread count vs output bytes. Mesa reads LP_NUM_THREADS once per process (when the first
// context is created), so each setting runs in a child process: this binary re-run with a filter
// selecting GlDeterminismChild and SPUME_GL_CHILD_OUT naming where to write the raw float buffers.
#include <gtest/gtest.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "gl/surface_pass.h"
#include "surface/mesh_primitives.h"

namespace spume {
namespace {

size_t thread_count_now() {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

// Runs in the child: water, a sphere half in it, the ground, sun in view.
TEST(GlDeterminismChild, Render) {
  const char* out = std::getenv("SPUME_GL_CHILD_OUT");
  if (!out) GTEST_SKIP() << "runs only as a child of GlDeterminism";
  const size_t before = thread_count_now();
  const TriangleMesh water = make_box_mesh(Vec3f(-3, 0, -3), Vec3f(3, 0.6f, 3));
  const TriangleMesh ball = make_sphere_mesh(Vec3f(0.5f, 0.6f, 0), 0.5f);
  SurfaceScene scene;
  scene.fluid = &water;
  scene.solids.push_back({&ball, Vec3f(0.8f, 0.5f, 0.2f), Vec3f::Zero()});
  scene.environment.sun_direction = Vec3f(0.2f, 0.4f, -1.0f).normalized();
  Camera cam;
  cam.position = Vec3f(0, 2.5f, 5), cam.target = Vec3f(0, 0.4f, 0), cam.width = 320, cam.height = 180;
  SurfacePass pass(SurfacePassOptions{.supersample = 2, .gl = {}});
  const SurfaceImage img = pass.render(scene, cam);
  std::ofstream f(out, std::ios::binary);
  const size_t threads = thread_count_now() - before;
  f.write(reinterpret_cast<const char*>(&threads), sizeof threads);
  f.write(reinterpret_cast<const char*>(img.colour.rgb.data()), std::streamsize(img.colour.rgb.size() * sizeof(Vec3f)));
  f.write(reinterpret_cast<const char*>(img.depth.data()), std::streamsize(img.depth.size() * sizeof(float)));
  f.write(reinterpret_cast<const char*>(img.opaque_depth.data()),
          std::streamsize(img.opaque_depth.size() * sizeof(float)));
}

std::string run_child(const std::string& lp_threads) {
  char exe[PATH_MAX] = {};
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n <= 0) return {};
  const auto path =
      std::filesystem::temp_directory_path() / ("spume_gl_child_" + std::to_string(getpid()) + "_" + lp_threads);
  const std::string cmd = "LP_NUM_THREADS=" + lp_threads + " SPUME_GL_CHILD_OUT=" + path.string() + " " + exe +
                          " --gtest_filter=GlDeterminismChild.Render > /dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) return {};
  std::ifstream f(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::filesystem::remove(path);
  return bytes;
}

TEST(GlDeterminism, SameBytesForAnyLlvmpipeThreadCount) {
  const std::string zero = run_child("0"), two = run_child("2"), four = run_child("4");
  ASSERT_GT(zero.size(), sizeof(size_t)) << "child render failed";
  ASSERT_EQ(zero.size(), two.size());
  ASSERT_EQ(zero.size(), four.size());
  size_t threads[3];
  std::memcpy(&threads[0], zero.data(), sizeof(size_t));
  std::memcpy(&threads[1], two.data(), sizeof(size_t));
  std::memcpy(&threads[2], four.data(), sizeof(size_t));
  std::printf("llvmpipe threads started: LP_NUM_THREADS=0 -> %zu, 2 -> %zu, 4 -> %zu\n", threads[0], threads[1],
              threads[2]);
  EXPECT_LT(threads[0], threads[2]) << "LP_NUM_THREADS had no effect";
  EXPECT_TRUE(zero.compare(sizeof(size_t), std::string::npos, two, sizeof(size_t)) == 0) << "0 vs 2 threads";
  EXPECT_TRUE(zero.compare(sizeof(size_t), std::string::npos, four, sizeof(size_t)) == 0) << "0 vs 4 threads";
}

}  // namespace
}  // namespace spume

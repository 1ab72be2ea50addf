// The child process of the GL determinism test (tests/render/gl_determinism_test.cpp): llvmpipe reads
// LP_NUM_THREADS when the first context is made, so each thread count needs a fresh process. It draws
// water, a sphere half in it, the ground and the sun in view, and writes the number of threads GL
// started, then the raw float colour and depth buffers, to the file named by its one argument.
#include <climits>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "render/gl/surface_pass.h"
#include "render/surface/mesh_primitives.h"

namespace {

size_t thread_count_now() {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace spume;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT\n", argv[0]);
    return 2;
  }
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
  std::ofstream f(argv[1], std::ios::binary);
  const size_t threads = thread_count_now() - before;
  f.write(reinterpret_cast<const char*>(&threads), sizeof threads);
  f.write(reinterpret_cast<const char*>(img.colour.rgb.data()), std::streamsize(img.colour.rgb.size() * sizeof(Vec3f)));
  f.write(reinterpret_cast<const char*>(img.depth.data()), std::streamsize(img.depth.size() * sizeof(float)));
  f.write(reinterpret_cast<const char*>(img.opaque_depth.data()), std::streamsize(img.opaque_depth.size() * sizeof(float)));
  return f ? 0 : 1;
}

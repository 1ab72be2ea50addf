// Taubin smoothing of the reconstructed surface: neighbours of a known mesh, noisy normals and
// positions on a sphere brought back towards the sphere's without shrinking it, the lattice's ripple
// on a particle box damped, and thread-count determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

#include "sim/core/parallel.h"
#include "render/surface/mesh_primitives.h"
#include "render/surface/mesh_smoothing.h"
#include "render/surface/reconstruct.h"

namespace spume {
namespace {

float degrees(float cosine) { return std::acos(std::clamp(cosine, -1.0f, 1.0f)) * 180.0f / std::numbers::pi_v<float>; }

// A latitude-longitude sphere whose vertices shared by the seam and poles are merged, so the umbrella
// operator sees one closed surface (make_sphere_mesh duplicates the seam column).
TriangleMesh welded_sphere(float radius, int rings, int segments) {
  const TriangleMesh raw = make_sphere_mesh(Vec3f::Zero(), radius, rings, segments);
  TriangleMesh m;
  std::vector<uint32_t> remap(raw.vertices.size());
  for (size_t i = 0; i < raw.vertices.size(); ++i) {
    size_t j = 0;
    while (j < m.vertices.size() && (m.vertices[j] - raw.vertices[i]).norm() > 1e-5f * radius) ++j;
    if (j == m.vertices.size()) m.vertices.push_back(raw.vertices[i]);
    remap[i] = uint32_t(j);
  }
  for (size_t t = 0; t < raw.triangle_count(); ++t) {
    const uint32_t a = remap[raw.indices[3 * t]], b = remap[raw.indices[3 * t + 1]], c = remap[raw.indices[3 * t + 2]];
    if (a != b && b != c && c != a) m.indices.insert(m.indices.end(), {a, b, c});
  }
  for (const Vec3f& v : m.vertices) m.normals.push_back(v.normalized());
  return m;
}

TEST(MeshSmoothing, NeighboursOfABox) {
  // make_box_mesh gives each face its own 4 vertices: a vertex has its face's two edge neighbours and
  // the diagonal one of the triangle split.
  const TriangleMesh box = make_box_mesh(Vec3f::Zero(), Vec3f::Ones());
  const VertexNeighbours nb = vertex_neighbours(box);
  ASSERT_EQ(nb.start.size(), box.vertices.size() + 1);
  size_t with_diagonal = 0;
  for (size_t i = 0; i < box.vertices.size(); ++i) {
    const uint32_t count = nb.start[i + 1] - nb.start[i];
    EXPECT_TRUE(count == 2 || count == 3) << "vertex " << i;
    with_diagonal += count == 3;
    for (uint32_t k = nb.start[i]; k < nb.start[i + 1]; ++k) {
      EXPECT_NE(nb.index[k], i);
      if (k > nb.start[i]) {
        EXPECT_LT(nb.index[k - 1], nb.index[k]) << "ascending, no repeats";
      }
      const Vec3f d = box.vertices[nb.index[k]] - box.vertices[i];
      EXPECT_TRUE(std::abs(d.norm() - 1.0f) < 1e-6f || std::abs(d.norm() - std::sqrt(2.0f)) < 1e-6f);
    }
  }
  EXPECT_EQ(with_diagonal, 12u) << "two per face";
}

// Exact radial normals on a sphere stay radial; normals tilted at random by up to 20 degrees come
// closer to radial: white noise spreads over the whole spectrum, and 8 lambda|mu iterations damp its
// upper half about tenfold and its lower half little, so the mean angle at least halves.
TEST(MeshSmoothing, NormalsOnASphere) {
  TriangleMesh sphere = welded_sphere(1.0f, 48, 96);
  const VertexNeighbours nb = vertex_neighbours(sphere);
  TriangleMesh exact = sphere;
  smooth_normals(exact, nb, 8);
  float worst_exact = 0;
  for (size_t i = 0; i < exact.vertices.size(); ++i)
    worst_exact = std::max(worst_exact, degrees(exact.normals[i].dot(exact.vertices[i].normalized())));
  EXPECT_LT(worst_exact, 0.5f);

  std::mt19937 rng(3);
  std::normal_distribution<float> g(0.0f, 1.0f);
  double before = 0, after = 0;
  for (Vec3f& n : sphere.normals) {
    Vec3f tangent(g(rng), g(rng), g(rng));
    tangent -= tangent.dot(n) * n;
    n = (n + std::tan(20.0f * std::numbers::pi_v<float> / 180.0f) * std::min(tangent.norm(), 1.0f) *
                 tangent.normalized())
            .normalized();
  }
  for (size_t i = 0; i < sphere.vertices.size(); ++i) before += degrees(sphere.normals[i].dot(sphere.vertices[i]));
  smooth_normals(sphere, nb, 8);
  for (size_t i = 0; i < sphere.vertices.size(); ++i) {
    EXPECT_NEAR(sphere.normals[i].norm(), 1.0f, 1e-5f);
    after += degrees(sphere.normals[i].dot(sphere.vertices[i]));
  }
  before /= double(sphere.vertices.size()), after /= double(sphere.vertices.size());
  EXPECT_GT(before, 8.0);
  EXPECT_LT(after, before / 2.0) << "mean angle to radial: " << before << " -> " << after << " deg";
}

// Positions and normals smoothed together are the values of smoothing one and then the other, bit
// for bit (the reconstruction smooths them together), and both change.
TEST(MeshSmoothing, SmoothingBothAtOnceEqualsOneAfterTheOther) {
  TriangleMesh noisy = welded_sphere(1.0f, 24, 48);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.05f, 0.05f);
  for (Vec3f& v : noisy.vertices) v *= 1.0f + u(rng);
  for (Vec3f& n : noisy.normals) n = (n + Vec3f(u(rng), u(rng), u(rng))).normalized();
  const VertexNeighbours nb = vertex_neighbours(noisy);
  TriangleMesh apart = noisy, together = noisy;
  smooth_positions(apart, nb, 8);
  smooth_normals(apart, nb, 8);
  smooth_surface(together, nb, 8);
  ASSERT_EQ(together.vertices.size(), apart.vertices.size());
  EXPECT_EQ(std::memcmp(together.vertices.data(), apart.vertices.data(), apart.vertices.size() * sizeof(Vec3f)), 0);
  EXPECT_EQ(std::memcmp(together.normals.data(), apart.normals.data(), apart.normals.size() * sizeof(Vec3f)), 0);
  EXPECT_NE(together.vertices, noisy.vertices);
  EXPECT_NE(together.normals, noisy.normals);
}

// Radial noise of 2% on a unit sphere: Taubin smoothing at least halves it (white noise, as above) and
// keeps the mean radius within 0.2%.
TEST(MeshSmoothing, PositionsOnASphereLoseNoiseNotSize) {
  TriangleMesh sphere = welded_sphere(1.0f, 48, 96);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.02f, 0.02f);
  for (Vec3f& v : sphere.vertices) v *= 1.0f + u(rng);
  auto radius_stats = [](const TriangleMesh& m) {
    double mean = 0, dev = 0;
    for (const Vec3f& v : m.vertices) mean += v.norm();
    mean /= double(m.vertices.size());
    for (const Vec3f& v : m.vertices) dev += (v.norm() - mean) * (v.norm() - mean);
    return std::pair{mean, std::sqrt(dev / double(m.vertices.size()))};
  };
  const auto [mean0, dev0] = radius_stats(sphere);
  const VertexNeighbours nb = vertex_neighbours(sphere);
  smooth_positions(sphere, nb, 8);
  const auto [mean1, dev1] = radius_stats(sphere);
  EXPECT_LT(dev1, dev0 / 2.0);
  EXPECT_NEAR(mean1, mean0, 0.002);
}

// Marching cubes over a particle box reproduces the lattice as a ripple on the flat faces: the median
// angle between the vertex normals and the face normal falls with smoothing while the vertices stay
// as close to the faces as before.
TEST(MeshSmoothing, LatticeRippleOnABoxIsDamped) {
  constexpr float r = 0.01f;
  const int n = 16;
  std::vector<Vec3f> particles;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) particles.push_back(2 * r * Vec3f(i + 0.5f, j + 0.5f, k + 0.5f));
  const float side = n * 2 * r;
  auto measure = [&](int smoothing) {
    SurfaceParams p;
    p.particle_radius = r;
    p.smoothing = smoothing;
    const TriangleMesh m = reconstruct_surface(particles, p);
    std::vector<float> angles;
    double distance = 0;
    size_t on_faces = 0;
    for (size_t i = 0; i < m.vertices.size(); ++i) {
      // Vertices well inside a face (farther than 2h from every edge): the face normal is exact there.
      const Vec3f& v = m.vertices[i];
      int axis = -1, inside = 0;
      for (int a = 0; a < 3; ++a) {
        if (v[a] > 8 * r && v[a] < side - 8 * r)
          ++inside;
        else
          axis = a;
      }
      if (inside != 2 || axis < 0) continue;
      Vec3f normal = Vec3f::Zero();
      normal[axis] = v[axis] < side / 2 ? -1.0f : 1.0f;
      angles.push_back(degrees(m.normals[i].dot(normal)));
      distance += std::abs(v[axis] < side / 2 ? v[axis] : v[axis] - side);
      ++on_faces;
    }
    std::nth_element(angles.begin(), angles.begin() + ptrdiff_t(angles.size() / 2), angles.end());
    return std::pair{angles[angles.size() / 2], distance / double(on_faces) / r};
  };
  const auto [ripple0, distance0] = measure(0);
  const auto [ripple8, distance8] = measure(8);
  EXPECT_GT(ripple0, 0.5f) << "the lattice shows in the unsmoothed normals";
  EXPECT_LT(ripple8, ripple0 / 3.0f) << ripple0 << " -> " << ripple8 << " deg";
  EXPECT_LT(distance8, distance0 + 0.01) << "in units of r: " << distance0 << " -> " << distance8;
}

TEST(MeshSmoothing, SameBytesForOneAndTwoThreads) {
  TriangleMesh sphere = welded_sphere(1.0f, 32, 64);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.05f, 0.05f);
  for (Vec3f& v : sphere.vertices) v *= 1.0f + u(rng);
  TriangleMesh one = sphere, two = sphere;
  set_thread_count(1);
  smooth_positions(one, vertex_neighbours(one), 5);
  smooth_normals(one, vertex_neighbours(one), 5);
  set_thread_count(2);
  smooth_positions(two, vertex_neighbours(two), 5);
  smooth_normals(two, vertex_neighbours(two), 5);
  set_thread_count(0);
  EXPECT_EQ(std::memcmp(one.vertices.data(), two.vertices.data(), one.vertices.size() * sizeof(Vec3f)), 0);
  EXPECT_EQ(std::memcmp(one.normals.data(), two.normals.data(), one.normals.size() * sizeof(Vec3f)), 0);
}

}  // namespace
}  // namespace spume

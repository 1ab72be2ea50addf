#include "render/surface/mesh_smoothing.h"

#include <algorithm>
#include <array>

#include "sim/core/parallel.h"

namespace spume {
namespace {

// One umbrella step x_i += w (mean of the neighbours - x_i) on each of the K fields, from `from` into
// `to`; the neighbours are summed in ascending order, so every value is the same for any split of the
// loop. Fields smoothed together (positions and normals) read the neighbour lists once.
template <size_t K>
void umbrella_step(const std::array<std::vector<Vec3f>*, K>& from, const std::array<std::vector<Vec3f>*, K>& to,
                   const VertexNeighbours& nb, float w) {
  parallel_for(from[0]->size(), 1024, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const uint32_t first = nb.start[i], last = nb.start[i + 1];
      std::array<Vec3f, K> sum;
      for (size_t f = 0; f < K; ++f) sum[f] = Vec3f::Zero();
      for (uint32_t k = first; k < last; ++k)
        for (size_t f = 0; f < K; ++f) sum[f] += (*from[f])[nb.index[k]];
      for (size_t f = 0; f < K; ++f) {
        const Vec3f& x = (*from[f])[i];
        (*to[f])[i] = first == last ? x : Vec3f(x + w * (sum[f] / float(last - first) - x));
      }
    }
  });
}

// Taubin's lambda|mu iterations on each of the K fields.
template <size_t K>
void taubin(const std::array<std::vector<Vec3f>*, K>& x, const VertexNeighbours& nb, int iterations) {
  std::array<std::vector<Vec3f>, K> tmp;
  std::array<std::vector<Vec3f>*, K> y;
  for (size_t f = 0; f < K; ++f) tmp[f].resize(x[f]->size()), y[f] = &tmp[f];
  for (int k = 0; k < iterations; ++k) {
    umbrella_step(x, y, nb, kTaubinLambda);
    umbrella_step(y, x, nb, kTaubinMu);
  }
}

// Unit normals from smoothed ones; one whose neighbourhood cancelled out keeps its old direction.
void renormalise(const std::vector<Vec3f>& smoothed, std::vector<Vec3f>& normals) {
  parallel_for(smoothed.size(), 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const float len = smoothed[i].norm();
      if (len > 1e-6f) normals[i] = smoothed[i] / len;
    }
  });
}

}  // namespace

VertexNeighbours vertex_neighbours(const TriangleMesh& mesh) {
  const size_t n = mesh.vertices.size();
  // Every triangle edge in both directions, bucketed by its first vertex (counting sort; an edge
  // shared by two triangles lands twice), then each bucket sorted and its repeats dropped.
  std::vector<uint32_t> count(n + 1, 0);
  auto each_edge = [&](auto&& fn) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
      for (size_t c = 0; c < 3; ++c) {
        const uint32_t a = mesh.indices[t + c], b = mesh.indices[t + (c + 1) % 3];
        if (a != b) fn(a, b), fn(b, a);
      }
  };
  each_edge([&](uint32_t a, uint32_t) { ++count[a + 1]; });
  for (size_t i = 0; i < n; ++i) count[i + 1] += count[i];
  std::vector<uint32_t> all(count[n]), fill(count.begin(), count.end() - 1);
  each_edge([&](uint32_t a, uint32_t b) { all[fill[a]++] = b; });
  std::vector<uint32_t> unique_count(n + 1, 0);
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const auto first = all.begin() + count[i], last = all.begin() + count[i + 1];
      std::sort(first, last);
      unique_count[i + 1] = uint32_t(std::unique(first, last) - first);
    }
  });
  VertexNeighbours nb;
  nb.start.resize(n + 1);
  nb.start[0] = 0;
  for (size_t i = 0; i < n; ++i) nb.start[i + 1] = nb.start[i] + unique_count[i + 1];
  nb.index.resize(nb.start[n]);
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i)
      std::copy_n(all.begin() + count[i], nb.start[i + 1] - nb.start[i], nb.index.begin() + nb.start[i]);
  });
  return nb;
}

void smooth_positions(TriangleMesh& mesh, const VertexNeighbours& neighbours, int iterations) {
  taubin<1>({&mesh.vertices}, neighbours, iterations);
}

void smooth_normals(TriangleMesh& mesh, const VertexNeighbours& neighbours, int iterations) {
  if (mesh.normals.size() != mesh.vertices.size()) return;
  std::vector<Vec3f> n = mesh.normals;
  taubin<1>({&n}, neighbours, iterations);
  renormalise(n, mesh.normals);
}

void smooth_surface(TriangleMesh& mesh, const VertexNeighbours& neighbours, int iterations) {
  if (mesh.normals.size() != mesh.vertices.size()) return smooth_positions(mesh, neighbours, iterations);
  std::vector<Vec3f> n = mesh.normals;
  taubin<2>({&mesh.vertices, &n}, neighbours, iterations);
  renormalise(n, mesh.normals);
}

}  // namespace spume

#include "sim/grid/distance_transform.h"

#include <cmath>
#include <limits>

#include "sim/core/parallel.h"

namespace spume {
namespace {

// One line: f (squared distances so far, +inf where unknown) becomes min over q of (p - q)^2 + f[q].
// v, z: the parabolas of the lower envelope and the boundaries between them (scratch, sized n and n + 1).
void transform_line(std::vector<float>& f, std::vector<float>& out, std::vector<int64_t>& v, std::vector<float>& z) {
  const int64_t n = int64_t(f.size());
  constexpr float inf = std::numeric_limits<float>::infinity();
  int64_t k = -1;
  for (int64_t q = 0; q < n; ++q) {
    if (!std::isfinite(f[q])) continue;
    for (;;) {
      if (k < 0) {
        v[0] = q, z[0] = -inf, z[1] = inf, k = 0;
        break;
      }
      const int64_t p = v[k];
      const float s = float(((double(f[q]) + double(q) * double(q)) - (double(f[p]) + double(p) * double(p))) /
                            double(2 * (q - p)));
      if (s <= z[k]) {
        --k;
        continue;
      }
      ++k, v[k] = q, z[k] = s, z[k + 1] = inf;
      break;
    }
  }
  if (k < 0) {
    out.assign(size_t(n), inf);
    return;
  }
  int64_t j = 0;
  for (int64_t q = 0; q < n; ++q) {
    while (z[j + 1] < float(q)) ++j;
    const float d = float(q - v[j]);
    out[q] = d * d + f[v[j]];
  }
}

// The pass along axis `a` over every line of the grid.
void transform_axis(std::vector<float>& d, const std::array<int64_t, 3>& dims, int a) {
  const int64_t stride[3] = {1, dims[0], dims[0] * dims[1]};
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const int64_t length = dims[a], across = dims[b], step_a = stride[a], step_b = stride[b], step_c = stride[c];
  const size_t lines = size_t(dims[b] * dims[c]);
  parallel_for(lines, 64, [&d, length, across, step_a, step_b, step_c](size_t begin, size_t end) {
    const size_t n = size_t(length);
    std::vector<float> f(n), out(n), z(n + 1);
    std::vector<int64_t> v(n);
    for (size_t l = begin; l < end; ++l) {
      const int64_t start = int64_t(l) % across * step_b + int64_t(l) / across * step_c;
      for (int64_t i = 0; i < length; ++i) f[size_t(i)] = d[size_t(start + i * step_a)];
      transform_line(f, out, v, z);
      for (int64_t i = 0; i < length; ++i) d[size_t(start + i * step_a)] = out[size_t(i)];
    }
  });
}

}  // namespace

std::vector<float> squared_distance_to_seeds(const std::vector<uint8_t>& seed, const std::array<int64_t, 3>& dims) {
  std::vector<float> d(seed.size());
  for (size_t c = 0; c < seed.size(); ++c) d[c] = seed[c] ? 0.0f : std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) transform_axis(d, dims, a);
  return d;
}

}  // namespace spume

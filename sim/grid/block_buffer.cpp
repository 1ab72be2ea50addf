#include "sim/grid/block_buffer.h"

#include "sim/core/error.h"

namespace spume {

void BlockBuffer::resize(size_t n, size_t attribute_count) {
  x_.resize(n), y_.resize(n), z_.resize(n), index_.resize(n);
  attributes_.resize(attribute_count);
  for (auto& a : attributes_)
    for (auto& c : a) c.resize(n);
}

// Fills [used, size()) with far-away points carrying zero attributes.
void BlockBuffer::pad(size_t used) {
  for (size_t j = used; j < x_.size(); ++j) {
    x_[j] = y_[j] = z_[j] = kFarAway;
    index_[j] = UINT32_MAX;
    for (auto& a : attributes_)
      for (auto& c : a) c[j] = 0.0f;
  }
}

void BlockBuffer::gather(const NeighbourGrid& grid, uint32_t key,
                         std::initializer_list<std::span<const Vec3f>> attributes) {
  const auto ranges = grid.block_ranges(key);
  size_t count = 0;
  for (const auto& [b, e] : ranges) count += e - b;
  resize((count + kLanes - 1) / kLanes * kLanes, attributes.size());
  const auto points = grid.sorted_points();
  size_t k = 0;
  for (const auto& [b, e] : ranges)
    for (uint32_t j = b; j < e; ++j, ++k) {
      x_[k] = points[j].x(), y_[k] = points[j].y(), z_[k] = points[j].z();
      index_[k] = j;
      size_t a = 0;
      for (const auto& attribute : attributes) {
        for (int c = 0; c < 3; ++c) attributes_[a][size_t(c)][k] = attribute[j][c];
        ++a;
      }
    }
  pad(k);
}

void BlockBuffer::gather_within(const BlockBuffer& source, const Aabb& box) {
  const size_t n = source.size(), attribute_count = source.attributes_.size();
  resize(n, attribute_count);  // an upper bound; shrunk below
  // Raw pointers, so the compiler need not reload the nested vectors after every store.
  constexpr size_t kMaxAttributes = 4;
  if (attribute_count > kMaxAttributes) fail("block buffer: ", attribute_count, " attributes, at most 4 supported");
  const float* from[kMaxAttributes * 3];
  float* to[kMaxAttributes * 3];
  for (size_t a = 0; a < attribute_count; ++a)
    for (size_t c = 0; c < 3; ++c) {
      from[a * 3 + c] = source.attributes_[a][c].data();
      to[a * 3 + c] = attributes_[a][c].data();
    }
  const size_t columns = attribute_count * 3;
  const float *sx = source.x_.data(), *sy = source.y_.data(), *sz = source.z_.data();
  const uint32_t* si = source.index_.data();
  float *dx = x_.data(), *dy = y_.data(), *dz = z_.data();
  uint32_t* di = index_.data();
  const float x0 = box.min.x(), y0 = box.min.y(), z0 = box.min.z();
  const float x1 = box.max.x(), y1 = box.max.y(), z1 = box.max.z();
  // Branch-free: every point is written at slot k, and k advances only past the ones inside.
  size_t k = 0;
  for (size_t j = 0; j < n; ++j) {
    const float x = sx[j], y = sy[j], z = sz[j];
    const bool in = (x >= x0) & (x <= x1) & (y >= y0) & (y <= y1) & (z >= z0) & (z <= z1);
    dx[k] = x, dy[k] = y, dz[k] = z, di[k] = si[j];
    for (size_t c = 0; c < columns; ++c) to[c][k] = from[c][j];
    k += in ? 1 : 0;
  }
  resize((k + kLanes - 1) / kLanes * kLanes, attribute_count);
  pad(k);
}

}  // namespace spume

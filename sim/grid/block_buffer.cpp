#include "block_buffer.h"

namespace spume {

void BlockBuffer::gather(const NeighbourGrid& grid, uint32_t key,
                         std::initializer_list<std::span<const Vec3f>> attributes) {
  x_.clear(), y_.clear(), z_.clear(), index_.clear();
  attributes_.resize(attributes.size());
  for (auto& a : attributes_)
    for (auto& c : a) c.clear();
  const auto points = grid.sorted_points();
  for (const auto& [b, e] : grid.block_ranges(key))
    for (uint32_t j = b; j < e; ++j) {
      x_.push_back(points[j].x()), y_.push_back(points[j].y()), z_.push_back(points[j].z());
      index_.push_back(j);
      size_t a = 0;
      for (const auto& attribute : attributes) {
        for (int c = 0; c < 3; ++c) attributes_[a][size_t(c)].push_back(attribute[j][c]);
        ++a;
      }
    }
  while (x_.size() % kLanes != 0) {
    x_.push_back(kFarAway), y_.push_back(kFarAway), z_.push_back(kFarAway);
    index_.push_back(UINT32_MAX);
    for (auto& a : attributes_)
      for (auto& c : a) c.push_back(0.0f);
  }
}

}  // namespace spume

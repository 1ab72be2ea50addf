#pragma once
// Exact Euclidean distance transform on a dense 3D grid (Felzenszwalb and Huttenlocher 2012): the
// squared distance, in cells, from every cell to the nearest seed cell, as three passes of a 1D
// lower envelope of parabolas, one per axis.
#include <array>
#include <cstdint>
#include <vector>

namespace spume {

// `seed` holds dims[0] x dims[1] x dims[2] flags, x fastest. Returns the squared distance in cells
// from each cell's centre to the nearest seed's centre; where there is no seed at all, +infinity.
std::vector<float> squared_distance_to_seeds(const std::vector<uint8_t>& seed, const std::array<int64_t, 3>& dims);

}  // namespace spume

#pragma once
// Leaving isolated particles out of the surface (Ihmsen et al. 2012 reconstruct only the fluid body:
// stragglers with few neighbours are spray, drawn by the volume pass, and must not become blobs).
#include <cstdint>
#include <span>
#include <vector>

#include "sim/core/vec.h"

namespace spume {

// Ascending input indices of the particles with at least `min_neighbours` OTHER particles closer than
// `support` (m). min_neighbours <= 0 keeps every particle. Deterministic for any thread count.
std::vector<uint32_t> connected_particles(std::span<const Vec3f> points, float support, int min_neighbours);

}  // namespace spume

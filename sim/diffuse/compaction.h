#pragma once
// Reorders the diffuse particles' columns one at a time, each through a buffer that is idle at that
// moment, instead of through a second whole set of columns: a frame of N particles holds about 28 bytes
// a particle less (tests/bench/RESULTS.md §17).
#include <span>
#include <vector>

#include "sim/core/frames.h"
#include "sim/core/huge_pages.h"
#include "sim/core/parallel.h"

namespace spume {

// Buffers a compaction may take over: their contents are garbage afterwards (they hold an old column).
struct CompactionBuffers {
  std::vector<Vec3f>& vectors;    // any idle array of Vec3f
  std::vector<float>& floats;     // any idle array of float
  std::vector<uint64_t>& ids;     // kept for the purpose
  std::vector<DiffuseType>& types;  // kept for the purpose
};

// column := column[order[0]], column[order[1]], ...; `into` receives the old buffer. `into` gets room
// for `capacity` elements when it has less, so that the next step's newborns rarely move the column.
template <typename T>
void gather_into(std::vector<T>& column, std::vector<T>& into, std::span<const uint32_t> order, size_t capacity) {
  if (into.capacity() < capacity) {
    std::vector<T>().swap(into);  // nothing in it is kept: freed before the larger block is taken
    reserve_in_huge_pages(into, capacity);
  }
  into.resize(order.size());
  parallel_for(order.size(), 1 << 14, [&](size_t b, size_t e) {
    for (size_t k = b; k < e; ++k) into[k] = column[order[k]];
  });
  column.swap(into);
}

// particles := particles[order[k]] for every k, column by column, with room for an eighth more.
inline void compact(DiffuseFrame& particles, std::span<const uint32_t> order, CompactionBuffers buffers) {
  const size_t room = order.size() + order.size() / 8;
  gather_into(particles.positions, buffers.vectors, order, room);
  gather_into(particles.velocities, buffers.vectors, order, room);  // into the old positions' buffer
  gather_into(particles.lifetimes, buffers.floats, order, room);
  gather_into(particles.ids, buffers.ids, order, room);
  gather_into(particles.types, buffers.types, order, room);
}

}  // namespace spume

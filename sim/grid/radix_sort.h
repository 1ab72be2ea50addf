#pragma once
// Stable LSD radix sort of 32-bit keys carrying a 32-bit payload. Stable, so the result depends only
// on the input order (deterministic); linear time, for sorting millions of particles by cell.
#include <cstdint>
#include <vector>

namespace spume {

// Sorts indices 0..keys.size()-1 by keys (stable); only the low `key_bits` bits are examined.
std::vector<uint32_t> radix_sort_indices(const std::vector<uint32_t>& keys, int key_bits);

}  // namespace spume

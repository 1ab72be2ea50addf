#include "radix_sort.h"

#include <algorithm>

namespace spume {

std::vector<uint32_t> radix_sort_indices(const std::vector<uint32_t>& keys, int key_bits) {
  constexpr int kDigitBits = 11;
  constexpr uint32_t kBuckets = 1u << kDigitBits;
  const size_t n = keys.size();
  // Keys travel with their indices so that every pass reads sequentially.
  std::vector<uint32_t> key(keys), order(n), key_scratch(n), order_scratch(n);
  for (size_t i = 0; i < n; ++i) order[i] = uint32_t(i);
  std::vector<uint32_t> counts(kBuckets);
  for (int shift = 0; shift < std::max(key_bits, 1); shift += kDigitBits) {
    std::fill(counts.begin(), counts.end(), 0u);
    for (size_t i = 0; i < n; ++i) ++counts[(key[i] >> shift) & (kBuckets - 1)];
    uint32_t sum = 0;
    for (uint32_t& c : counts) {
      const uint32_t here = c;
      c = sum;
      sum += here;
    }
    for (size_t i = 0; i < n; ++i) {
      const uint32_t slot = counts[(key[i] >> shift) & (kBuckets - 1)]++;
      key_scratch[slot] = key[i];
      order_scratch[slot] = order[i];
    }
    key.swap(key_scratch);
    order.swap(order_scratch);
  }
  return order;
}

}  // namespace spume

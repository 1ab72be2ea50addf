#include "sim/core/radix_sort.h"

#include <algorithm>

#include "sim/core/huge_pages.h"
#include "sim/core/parallel.h"

namespace spume {

size_t RadixSorter::bytes() const {
  return held_bytes(order_) + held_bytes(keys_) + held_bytes(order_scratch_) + held_bytes(key_scratch_) +
         held_bytes(offsets_);
}

void RadixSorter::sort_input_keys(int key_bits) { sort(keys_, key_bits); }

void RadixSorter::sort(std::span<const uint32_t> keys, int key_bits) {
  const size_t n = keys.size();
  const int bits = std::clamp(key_bits, 1, 32);
  // Few passes of even width: 20 bits sort in 2 passes of 1024 buckets, which keeps the scatter's
  // write streams (2 per bucket) within the caches.
  const int passes = (bits + 10) / 11;
  const int digit_bits = (bits + passes - 1) / passes;
  const uint32_t buckets = 1u << digit_bits, mask = buckets - 1;

  // Fixed chunks, each counted and scattered by one task. A stable sort has one answer, so neither
  // the chunking nor the thread count can change the result.
  const size_t chunk_count = std::clamp<size_t>(n / (1 << 16), 1, 256);
  const size_t chunk = (n + chunk_count - 1) / chunk_count;
  offsets_.resize(chunk_count * buckets);  // [chunk][bucket] -> next output slot
  // All four are written whole before they are read. keys may be keys_ itself (sort_input_keys):
  // resizing it to its own size keeps it.
  for (std::vector<uint32_t>* v : {&order_, &keys_, &order_scratch_, &key_scratch_})
    resize_discarding_in_huge_pages(*v, n);

  // Keys travel with their indices so that every pass reads sequentially. The first pass reads the
  // caller's keys and the identity order directly.
  const uint32_t* key_in = keys.data();
  for (int pass = 0; pass < passes; ++pass) {
    const int shift = pass * digit_bits;
    const bool first = pass == 0;
    parallel_for(chunk_count, 1, [&](size_t cb, size_t ce) {
      for (size_t c = cb; c < ce; ++c) {
        uint32_t* count = &offsets_[c * buckets];
        std::fill(count, count + buckets, 0u);
        const size_t end = std::min(n, (c + 1) * chunk);
        for (size_t i = c * chunk; i < end; ++i) ++count[(key_in[i] >> shift) & mask];
      }
    });
    // Exclusive scan in (bucket, chunk) order: chunk c's share of a bucket follows chunks < c.
    uint32_t sum = 0;
    for (uint32_t b = 0; b < buckets; ++b)
      for (size_t c = 0; c < chunk_count; ++c) {
        uint32_t& slot = offsets_[c * buckets + b];
        const uint32_t here = slot;
        slot = sum;
        sum += here;
      }
    parallel_for(chunk_count, 1, [&](size_t cb, size_t ce) {
      for (size_t c = cb; c < ce; ++c) {
        uint32_t* next = &offsets_[c * buckets];
        const size_t end = std::min(n, (c + 1) * chunk);
        for (size_t i = c * chunk; i < end; ++i) {
          const uint32_t k = key_in[i];
          const uint32_t slot = next[(k >> shift) & mask]++;
          key_scratch_[slot] = k;
          order_scratch_[slot] = first ? uint32_t(i) : order_[i];
        }
      }
    });
    keys_.swap(key_scratch_);
    order_.swap(order_scratch_);
    key_in = keys_.data();
  }
}

std::vector<uint32_t> radix_sort_indices(const std::vector<uint32_t>& keys, int key_bits) {
  RadixSorter sorter;
  sorter.sort(keys, key_bits);
  return std::move(sorter.order());
}

}  // namespace spume

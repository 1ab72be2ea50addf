#pragma once
// Stable LSD radix sort of 32-bit keys carrying a 32-bit payload, parallel over fixed chunks. Stable,
// so the result depends only on the input order (deterministic for any thread count); linear time,
// for sorting millions of particles by cell.
#include <cstdint>
#include <span>
#include <vector>

namespace spume {

// Keeps its buffers between calls, so sorting every step touches no fresh memory.
class RadixSorter {
 public:
  // Sorts indices 0..keys.size()-1 by keys (stable); only the low `key_bits` bits are examined.
  void sort(std::span<const uint32_t> keys, int key_bits);
  // The same for keys written into input_keys() first, so that they need no array of the caller's:
  // the first pass reads them there and writes its output to the other key buffer.
  std::vector<uint32_t>& input_keys() { return keys_; }
  void sort_input_keys(int key_bits);
  const std::vector<uint32_t>& order() const { return order_; }        // input index of each sorted slot
  const std::vector<uint32_t>& sorted_keys() const { return keys_; }   // keys in sorted order
  std::vector<uint32_t>& order() { return order_; }
  size_t bytes() const;  // what its buffers hold

 private:
  std::vector<uint32_t> order_, keys_, order_scratch_, key_scratch_, offsets_;
};

// One-off form of RadixSorter::sort: the sorted order of indices.
std::vector<uint32_t> radix_sort_indices(const std::vector<uint32_t>& keys, int key_bits);

}  // namespace spume

#pragma once
// An uninitialised array for the caches' large scratch columns. Fresh memory costs a page fault per
// 4 KiB page on first touch (most of a large frame's encode time on a virtual machine: about 4 ms a
// MiB on this one, 2 ms with 2 MiB pages), and std::vector also zero-fills what is about to be
// overwritten; this buffer asks for 2 MiB pages (transparent huge pages, madvise), leaves the
// contents to the writer, and hands its memory back to a process-wide pool when it is freed, so
// that the next frame's columns reuse pages already mapped (scratch_pool below).
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

#include "sim/core/huge_pages.h"

namespace spume {

// How a block's owner writes it. Only written pages are mapped: a block written in part (a cache being
// assembled, each compressed chunk at its worst-case offset) keeps unmapped holes, which fault in again
// when the block serves an owner that writes it whole (a sort's scratch). So each kind goes back to
// its own kind of owner first.
enum class BlockWrites { Whole, InPart };

// The pool behind HugeBuffer: freed blocks are kept (up to scratch_pool_cap() of blocks in all, the oldest
// released first beyond that) and a request takes the smallest kept block that fits, when that block
// is at most twice the request, of its own kind if one fits. Block sizes are rounded up to 2 MiB
// (64 KiB in ordinary pages under 2 MiB) times 8..15 x a power of two, so that a frame slightly larger
// than the last still fits the last frame's blocks; when none fits, the largest kept block of at least half the request (of its own kind first)
// is grown in place of a fresh one (its pages move over, and only the growth is fresh). Thread-safe.
// A third of the machine's memory, at least 2 GiB (address space: only the touched pages are resident).
// A 100M-particle frame's cache encoder takes about 7 GiB of blocks; handed back to the system beyond
// a fixed 2 GiB cap, they had to be cleared again every frame (RESULTS.md §17.1).
size_t scratch_pool_cap();
void* scratch_take(size_t bytes, size_t& block_bytes, BlockWrites writes = BlockWrites::Whole);
void scratch_give_back(void* block, size_t block_bytes, BlockWrites writes = BlockWrites::Whole);
size_t scratch_pool_kept_bytes();  // memory held for reuse now
// Hands every kept block back to the system: for a stage done with its large arrays, so that the next
// stage in the same process (spume run's render after its simulation) does not carry them.
void scratch_pool_release();

template <typename T>
class HugeBuffer {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  HugeBuffer() = default;
  explicit HugeBuffer(size_t n, BlockWrites writes = BlockWrites::Whole) : writes_(writes) { resize(n); }
  HugeBuffer(HugeBuffer&& o) noexcept { swap(o); }
  HugeBuffer& operator=(HugeBuffer&& o) noexcept {
    HugeBuffer(std::move(o)).swap(*this);
    return *this;
  }
  ~HugeBuffer() {
    if (data_) scratch_give_back(data_, block_bytes_, writes_);
  }
  // Contents are unspecified after a resize that grows the buffer.
  void resize(size_t n) {
    if (n > capacity_) {
      size_t block = 0;
      T* p = static_cast<T*>(scratch_take(n * sizeof(T), block, writes_));
      if (data_) scratch_give_back(data_, block_bytes_, writes_);
      data_ = p, block_bytes_ = block, capacity_ = block / sizeof(T);
    }
    size_ = n;
  }
  size_t size() const { return size_; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }
  T* begin() { return data(); }
  T* end() { return data() + size_; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size_; }

 private:
  void swap(HugeBuffer& o) noexcept {
    std::swap(data_, o.data_), std::swap(size_, o.size_), std::swap(capacity_, o.capacity_);
    std::swap(block_bytes_, o.block_bytes_), std::swap(writes_, o.writes_);
  }
  T* data_ = nullptr;
  size_t size_ = 0, capacity_ = 0, block_bytes_ = 0;
  BlockWrites writes_ = BlockWrites::Whole;
};

}  // namespace spume

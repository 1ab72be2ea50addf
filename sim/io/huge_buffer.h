#pragma once
// An uninitialised array for the caches' large scratch columns. Fresh memory costs a page fault per
// 4 KiB page on first touch (most of a large frame's encode time on a virtual machine), and
// std::vector also zero-fills what is about to be overwritten; this buffer asks for 2 MiB pages
// (transparent huge pages, madvise) and leaves the contents to the writer.
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>

namespace spume {

// Asks for 2 MiB pages over the whole 2 MiB pages inside [p, p + bytes) (memory not yet touched, such as
// a vector's after reserve()): advice only.
inline void advise_huge_pages(void* p, size_t bytes) {
  constexpr uintptr_t kHuge = uintptr_t(2) << 20;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(p) + kHuge - 1) & ~(kHuge - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(p) + bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

template <typename T>
class HugeBuffer {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  HugeBuffer() = default;
  explicit HugeBuffer(size_t n) { resize(n); }
  // Contents are unspecified after a resize that grows the buffer.
  void resize(size_t n) {
    if (n > capacity_) {
      constexpr size_t kHuge = size_t(2) << 20;
      const size_t bytes = (n * sizeof(T) + kHuge - 1) / kHuge * kHuge;
      void* p = std::aligned_alloc(kHuge, bytes);
      if (!p) throw std::bad_alloc();
      madvise(p, bytes, MADV_HUGEPAGE);  // advice only: without huge pages it is an ordinary buffer
      data_.reset(static_cast<T*>(p));
      capacity_ = bytes / sizeof(T);
    }
    size_ = n;
  }
  size_t size() const { return size_; }
  T* data() { return data_.get(); }
  const T* data() const { return data_.get(); }
  T& operator[](size_t i) { return data_.get()[i]; }
  const T& operator[](size_t i) const { return data_.get()[i]; }
  T* begin() { return data(); }
  T* end() { return data() + size_; }

 private:
  struct Free {
    void operator()(T* p) const { std::free(p); }
  };
  std::unique_ptr<T, Free> data_;
  size_t size_ = 0, capacity_ = 0;
};

}  // namespace spume

#pragma once
// Large per-frame arrays (the renderer's screen bins, 16 B x 1.2 N; its colour field's lattice; its
// marching-cubes cases) without a zero-fill pass and, on Linux, backed by transparent huge pages (the
// kernel here runs THP in madvise mode): a 500 MB array otherwise costs ~125k page faults, a
// measurable share of a 15M-sphere frame (the lighthouse's 44 MB lattice: 455 -> 336 ms of the field
// on one core). Not named HugeBuffer: sim/io/huge_buffer.h has a different spume::HugeBuffer, and two
// class templates of one name in one program break the one-definition rule (the linker would merge
// same-T members).
#include <cstddef>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace spume {

template <typename T>
class HugePageArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

 public:
  HugePageArray() = default;
  explicit HugePageArray(size_t n) { allocate(n); }
  ~HugePageArray() { std::free(data_); }
  HugePageArray(HugePageArray&& o) noexcept
      : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)), capacity_(std::exchange(o.capacity_, 0)) {}
  HugePageArray& operator=(HugePageArray&& o) noexcept {
    std::swap(data_, o.data_), std::swap(size_, o.size_), std::swap(capacity_, o.capacity_);
    return *this;
  }
  HugePageArray(const HugePageArray&) = delete;
  HugePageArray& operator=(const HugePageArray&) = delete;

  // Discards the contents; elements are left uninitialised. Keeps the memory when it is large
  // enough: pages already touched cost no fault and no zeroing by the kernel.
  void allocate(size_t n) {
    size_ = n;
    if (n <= capacity_) return;
    std::free(data_);
    data_ = nullptr, capacity_ = 0;
    if (n == 0) return;
    constexpr size_t kHuge = size_t(2) << 20;
    const size_t bytes = n * sizeof(T);
    const size_t align = bytes >= kHuge ? kHuge : alignof(std::max_align_t);
    data_ = static_cast<T*>(std::aligned_alloc(align, (bytes + align - 1) / align * align));
    if (!data_) size_ = 0, throw std::bad_alloc();
    capacity_ = n;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (align == kHuge) madvise(data_, (bytes + align - 1) / align * align, MADV_HUGEPAGE);  // a hint; failure is harmless
#endif
  }

  size_t capacity() const { return capacity_; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  size_t size() const { return size_; }
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }

 private:
  T* data_ = nullptr;
  size_t size_ = 0, capacity_ = 0;
};

}  // namespace spume

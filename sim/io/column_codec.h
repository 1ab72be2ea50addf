#pragma once
// Compressed columns for spume's caches: one array of fixed-size values (ids, quantized positions...)
// byte- or bit-shuffled and compressed with Blosc (its zstd codec), cut into chunks of a fixed raw size
// (kColumnChunkBytes) that are compressed in parallel. The chunking depends on the column alone, and
// each chunk is compressed by one thread, so the bytes are the same for any thread count.
//
// Stored column: u64 raw bytes, u64 stored bytes (the chunks' total), then the Blosc chunks back to back.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "sim/io/huge_buffer.h"
#include "sim/io/io_bytes.h"

namespace spume {

constexpr size_t kColumnChunkBytes = size_t(1) << 20;

// A file being assembled in memory.
class CacheBytes {
 public:
  void reserve(size_t bytes);  // keeps the contents
  void append(const void* data, size_t bytes);
  template <typename T>
  void store(T v) {
    append(&v, sizeof v);  // little-endian host (spume_cache.cpp asserts it)
  }
  char* data() { return buffer_.data(); }
  const char* data() const { return buffer_.data(); }
  size_t size() const { return size_; }
  std::string_view view() const { return {buffer_.data(), size_}; }
  void resize(size_t bytes);  // within the reserved capacity, or growing it

 private:
  HugeBuffer<char> buffer_;
  size_t size_ = 0, capacity_ = 0;
};

// The most a column of `bytes` raw bytes can take stored, its 16-byte prefix included.
size_t column_bound(size_t bytes);

// Blosc's block, the unit zstd compresses on its own (it starts afresh at each one): fixed by the
// frame, never Blosc's choice, so that the bytes depend on the data alone.
constexpr size_t kSmallColumnBlockBytes = size_t(256) << 10;
constexpr size_t kLargeColumnBlockBytes = kColumnChunkBytes;  // a chunk is one block
// Frames of at least this many particles take the large blocks (column_block_bytes).
constexpr size_t kLargeBlockParticles = size_t(1) << 21;
// The block for the columns of a frame of `particles` particles.
size_t column_block_bytes(size_t particles);

// Appends the column of `bytes` bytes at data (values of `typesize` bytes) to out, compressed in
// blocks of `block_bytes` (column_block_bytes).
void append_column(CacheBytes& out, const void* data, size_t bytes, size_t typesize, bool bit_shuffle,
                   size_t block_bytes);

// Reads the next column from r into dst, which holds exactly `bytes`: fails naming the file and `what`
// when the column claims another size, runs past the file, or a chunk is corrupt.
void read_column(io::ByteReader& r, void* dst, size_t bytes, const char* what);
// Steps over the next column, of `bytes` raw bytes, without decoding it: fails as read_column does when
// it claims another size or runs past the file; its chunks are not looked at.
void skip_column(io::ByteReader& r, size_t bytes, const char* what);

}  // namespace spume

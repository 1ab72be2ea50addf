#include "sim/io/column_codec.h"

#include <blosc.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume {
namespace {

// zstd at its fastest level: bytes a particle on real frames, against LZ4 (Blosc's lz4): dam break
// frame 60 (1.2M) 10.95 / 11.66, wave frame 52 (317k) 11.39 / 13.09, tower (215k) 11.64 / 13.84; the
// goal is 12. LZ4 compresses and decompresses faster, but both beat the raw layout in the pipeline.
constexpr int kLevel = 1;
constexpr const char* kCodec = BLOSC_ZSTD_COMPNAME;
constexpr size_t kBloscHeader = BLOSC_MIN_HEADER_LENGTH;

size_t chunk_count(size_t bytes) { return (bytes + kColumnChunkBytes - 1) / kColumnChunkBytes; }

}  // namespace

void CacheBytes::reserve(size_t bytes) {
  if (bytes <= capacity_) return;
  HugeBuffer<char> bigger(bytes, BlockWrites::InPart);  // append_column writes its worst case in part
  if (size_ > 0) std::memcpy(bigger.data(), buffer_.data(), size_);
  buffer_ = std::move(bigger);
  capacity_ = bytes;
}

void CacheBytes::resize(size_t bytes) {
  if (bytes > capacity_) reserve(std::max(bytes, 2 * capacity_));
  size_ = bytes;
}

void CacheBytes::append(const void* data, size_t bytes) {
  const size_t at = size_;
  resize(size_ + bytes);
  if (bytes > 0) std::memcpy(buffer_.data() + at, data, bytes);
}

// One block a chunk compresses large frames faster and smaller: zstd keeps its context over 1 MiB
// instead of 256 KiB. Below about 2M particles a 1 MiB block spans two or three of a column's x, y
// and z planes, which bit-shuffle worse together, so small frames keep 256 KiB blocks (measured in
// tests/bench/RESULTS.md §5).
size_t column_block_bytes(size_t particles) {
  return particles >= kLargeBlockParticles ? kLargeColumnBlockBytes : kSmallColumnBlockBytes;
}

size_t column_bound(size_t bytes) { return 16 + bytes + chunk_count(bytes) * BLOSC_MAX_OVERHEAD; }

void append_column(CacheBytes& out, const void* data, size_t bytes, size_t typesize, bool bit_shuffle,
                   size_t block_bytes) {
  // Each chunk is compressed in place at its worst-case offset, then the chunks are moved together.
  const size_t chunks = chunk_count(bytes);
  const size_t start = out.size();
  constexpr size_t kSlot = kColumnChunkBytes + BLOSC_MAX_OVERHEAD;
  out.resize(start + column_bound(bytes));
  std::vector<size_t> packed(chunks);
  const char* src = static_cast<const char*>(data);
  char* base = out.data() + start + 16;
  parallel_for(chunks, 1, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c) {
      const size_t raw = std::min(kColumnChunkBytes, bytes - c * kColumnChunkBytes);
      const int got = blosc_compress_ctx(kLevel, bit_shuffle ? BLOSC_BITSHUFFLE : BLOSC_SHUFFLE, typesize, raw, src + c * kColumnChunkBytes,
                                         base + c * kSlot, raw + BLOSC_MAX_OVERHEAD, kCodec, block_bytes, 1);
      if (got <= 0) fail("Blosc could not compress a ", raw, "-byte chunk (error ", got, ")");
      packed[c] = size_t(got);
    }
  });
  size_t stored = 0;
  for (size_t c = 0; c < chunks; ++c) {
    if (stored != c * kSlot) std::memmove(base + stored, base + c * kSlot, packed[c]);
    stored += packed[c];
  }
  const uint64_t prefix[2] = {uint64_t(bytes), uint64_t(stored)};
  std::memcpy(out.data() + start, prefix, 16);
  out.resize(start + 16 + stored);
}

namespace {

// The next column's stored chunks, after checking its prefix against the `bytes` the caller expects.
std::string_view take_column(io::ByteReader& r, size_t bytes, const char* what) {
  const uint64_t raw = r.read<uint64_t>(what);
  if (raw != bytes)
    fail(r.where(), ": corrupt: the ", what, " column holds ", raw, " bytes; the header asks for ", bytes);
  const uint64_t stored = r.read<uint64_t>(what);
  if (stored > r.remaining())
    fail(r.where(), ": truncated or corrupt: the ", what, " column claims ", stored, " bytes; ", r.remaining(),
         " remain");
  return r.take(size_t(stored), what);
}

}  // namespace

void skip_column(io::ByteReader& r, size_t bytes, const char* what) { take_column(r, bytes, what); }

void read_column(io::ByteReader& r, void* dst, size_t bytes, const char* what) {
  const std::string_view column = take_column(r, bytes, what);
  // Every chunk's place first (chunk c holds raw bytes [c * kColumnChunkBytes, ...)), then in parallel.
  const size_t chunks = chunk_count(bytes);
  std::vector<size_t> offset(chunks + 1, 0);
  for (size_t c = 0; c < chunks; ++c) {
    const size_t at = offset[c];
    const size_t want = std::min(kColumnChunkBytes, bytes - c * kColumnChunkBytes);
    size_t nbytes = 0, cbytes = 0, checked = 0;
    if (column.size() - at < kBloscHeader ||
        (blosc_cbuffer_sizes(column.data() + at, &nbytes, &cbytes, &checked), cbytes > column.size() - at) ||
        blosc_cbuffer_validate(column.data() + at, cbytes, &checked) != 0 || nbytes != want)
      fail(r.where(), ": corrupt: chunk ", c, " of the ", what, " column is not a Blosc chunk of ", want, " bytes");
    offset[c + 1] = at + cbytes;
  }
  if (offset[chunks] != column.size())
    fail(r.where(), ": corrupt: the ", what, " column has ", column.size() - offset[chunks], " bytes after its chunks");
  char* out = static_cast<char*>(dst);
  parallel_for(chunks, 1, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c) {
      const size_t want = std::min(kColumnChunkBytes, bytes - c * kColumnChunkBytes);
      const int got = blosc_decompress_ctx(column.data() + offset[c], out + c * kColumnChunkBytes, want, 1);
      if (got < 0 || size_t(got) != want)
        fail(r.where(), ": corrupt: chunk ", c, " of the ", what, " column did not decompress");
    }
  });
}

}  // namespace spume

#include "sim/io/houdini_scf.h"

#include <blosc.h>

#include <cstdint>
#include <vector>

#include "sim/core/error.h"
#include "sim/core/out_of_memory.h"
#include "sim/io/io_bytes.h"

namespace spume {
namespace {

constexpr size_t kHeader = 12;          // "scf1" and 8 bytes
constexpr size_t kTrailerFixed = 12;    // int64 index size and "1fcs"
constexpr size_t kBloscHeader = BLOSC_MIN_HEADER_LENGTH;  // 16
struct Chunk {
  size_t offset, compressed, decompressed;
};

// The most a chunk of `compressed` bytes can hold, by its codec's densest code: LZ4 and BloscLZ spend a
// byte per 255 bytes of a long match, Snappy 3 bytes per 64, deflate about 1 per 1032, and Zstandard a
// 4-byte RLE block per 128 KiB (Blosc 1.21 on zeros: 251, 251, 21, 929 and 18316 to 1). Blosc's flags
// name the codec in their top 3 bits; a chunk stored uncompressed holds its own bytes less the header.
struct Codec {
  const char* name;
  uint64_t densest;
};
Codec chunk_codec(uint8_t flags, size_t offset, const std::string& where) {
  if (flags & BLOSC_MEMCPYED) return {"stored", 1};
  switch (flags >> 5) {
    case BLOSC_BLOSCLZ_FORMAT: return {"BloscLZ", 256};
    case BLOSC_LZ4_FORMAT: return {"LZ4", 256};
    case BLOSC_SNAPPY_FORMAT: return {"Snappy", 22};
    case BLOSC_ZLIB_FORMAT: return {"zlib", 1032};
    case BLOSC_ZSTD_FORMAT: return {"Zstandard", 32768};
  }
  fail(where, ": corrupt: Blosc chunk at offset ", offset, " names codec ", flags >> 5,
       "; Blosc's are 0 BloscLZ, 1 LZ4, 2 Snappy, 3 zlib, 4 Zstandard");
}

}  // namespace

bool has_scf_magic(std::string_view file) { return file.substr(0, 4) == "scf1"; }

uint64_t check_scf_ends(std::string_view head, std::string_view tail, uint64_t file_size, const std::string& where) {
  if (!has_scf_magic(head)) fail(where, ": not a .bgeo.sc file: it must start with 'scf1'");
  if (file_size < kHeader + kTrailerFixed || tail.size() < kTrailerFixed)
    fail(where, ": truncated: ", file_size, " bytes, too short for a .bgeo.sc file (header and index alone take ",
         kHeader + kTrailerFixed, ")");
  if (tail.substr(tail.size() - 4) != "1fcs")
    fail(where, ": truncated or corrupt: a .bgeo.sc file ends with its index and the bytes '1fcs', which are missing");
  const uint64_t index_bytes = io::load<uint64_t>(tail.data() + tail.size() - kTrailerFixed, io::Endian::Big);
  if (index_bytes % 8 != 0 || index_bytes > file_size - kHeader - kTrailerFixed)
    fail(where, ": corrupt: the index at the end claims ", index_bytes, " bytes in a file of ", file_size);
  return index_bytes;
}

std::string decompress_scf(std::string_view file, const std::string& where, ScfStats* stats) {
  const uint64_t index_bytes = check_scf_ends(file, file, file.size(), where);
  const size_t chunks_end = file.size() - kTrailerFixed - size_t(index_bytes);

  // All chunk headers first: nothing is decompressed from a file whose chunks do not fit.
  std::vector<Chunk> chunks;
  for (size_t pos = kHeader; pos < chunks_end;) {
    if (chunks_end - pos < kBloscHeader)
      fail(where, ": truncated or corrupt: ", chunks_end - pos, " bytes at offset ", pos,
           " cannot hold a Blosc chunk header (16 bytes)");
    const uint8_t version = uint8_t(file[pos]);
    if (version == 0 || version > BLOSC_VERSION_FORMAT)
      fail(where, ": corrupt: Blosc chunk at offset ", pos, " has format version ", int(version), "; allowed 1 to ",
           BLOSC_VERSION_FORMAT);
    size_t nbytes = 0, cbytes = 0, blocksize = 0;
    blosc_cbuffer_sizes(file.data() + pos, &nbytes, &cbytes, &blocksize);
    if (cbytes < kBloscHeader || cbytes > chunks_end - pos)
      fail(where, ": truncated or corrupt: Blosc chunk at offset ", pos, " claims ", cbytes,
           " compressed bytes; ", chunks_end - pos, " remain before the index");
    const Codec codec = chunk_codec(uint8_t(file[pos + 2]), pos, where);
    if (nbytes > BLOSC_MAX_BUFFERSIZE || nbytes > (cbytes - kBloscHeader) * codec.densest)
      fail(where, ": corrupt: Blosc chunk at offset ", pos, " claims ", nbytes, " decompressed bytes from ", cbytes,
           " compressed (", codec.name, "), more than its codec can hold in them (", codec.densest, " to 1",
           codec.densest > 1 ? ", its densest" : "", ")");
    chunks.push_back({pos, cbytes, nbytes});
    pos += cbytes;
  }
  if (chunks.empty()) fail(where, ": corrupt: a .bgeo.sc file without Blosc chunks");

  // Grown chunk by chunk: memory follows what decompresses, so a chunk that lies about its size costs
  // no more than its own claim before it is found out.
  std::string out;
  size_t at = 0;
  for (const Chunk& c : chunks) {
    allocating(str("decompressing ", where), c.decompressed, [&] { out.resize(at + c.decompressed); });
    size_t checked = 0;
    if (blosc_cbuffer_validate(file.data() + c.offset, c.compressed, &checked) != 0 || checked != c.decompressed)
      fail(where, ": corrupt: Blosc chunk at offset ", c.offset, " has an inconsistent header");
    const int got = blosc_decompress_ctx(file.data() + c.offset, out.data() + at, c.decompressed, 1);
    if (got < 0 || size_t(got) != c.decompressed)
      fail(where, ": corrupt: Blosc chunk at offset ", c.offset, " did not decompress (", got < 0 ? "error " : "got ",
           got, got < 0 ? "" : str(" bytes of ", c.decompressed), ")");
    at += c.decompressed;
  }
  if (stats) *stats = {chunks.size(), out.size()};
  return out;
}

}  // namespace spume

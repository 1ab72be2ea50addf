#pragma once
// Houdini's Blosc-compressed container (.bgeo.sc, "seekable compressed format"), as Houdini 18.5 writes
// it (seen in real files, not from a specification):
//   "scf1", 8 bytes (zero in every file seen), then Blosc chunks one after another (each with its own
//   16-byte Blosc header giving its compressed and decompressed sizes), then an index: n 8-byte big-endian
//   numbers, the int64 n*8 and the bytes "1fcs". The index tells where the chunks end; its numbers (chunk
//   offsets and sizes, for seeking) are not needed to read the file front to back.
#include <cstddef>
#include <string>
#include <string_view>

namespace spume {

struct ScfStats {
  size_t chunks = 0;
  size_t decompressed_bytes = 0;
};

bool has_scf_magic(std::string_view file);

// Its two ends checked before the whole file is read: the magic in `head` (its first bytes), and in
// `tail` (its last 12 or more) the closing "1fcs" and an index that fits a file of `file_size` bytes.
// Returns the index's size in bytes. `where` names the file in errors.
uint64_t check_scf_ends(std::string_view head, std::string_view tail, uint64_t file_size, const std::string& where);

// The decompressed bytes. Every chunk header is checked before anything is decompressed: it must lie
// inside the file, and claim no more than its codec can code in its bytes (LZ4, Houdini's: 256 to 1;
// the real files hold under 4 to 1). The output grows chunk by chunk, and each chunk must decompress to
// exactly what its header declares. `where` names the file in errors.
std::string decompress_scf(std::string_view file, const std::string& where, ScfStats* stats = nullptr);

}  // namespace spume

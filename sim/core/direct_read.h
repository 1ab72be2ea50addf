#pragma once
// Reads a file into memory, its whole 4 KiB blocks straight from the disk (O_DIRECT) when `data` is
// 4 KiB aligned, the rest through the page cache. A 15M-particle diffuse cache is 170 MB a frame:
// through the page cache it is read from the disk into the cache and then copied, or, freshly
// written, found there only if the cache kept it; read directly it costs the same whatever the cache
// holds (the caches are written directly too, core/atomic_file.h). File systems that refuse direct
// reads are read through the page cache.
#include <cstddef>
#include <filesystem>

namespace spume {

// Reads exactly `size` bytes from the start of `path` into data. Throws Error naming the file when it
// cannot be opened or holds fewer bytes.
void read_file_bytes(const std::filesystem::path& path, char* data, size_t size);

}  // namespace spume

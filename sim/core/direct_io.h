#pragma once
// Whole files between memory and disk, their whole 4 KiB blocks straight to and from the disk
// (O_DIRECT) when the memory is 4 KiB aligned, the rest through the page cache. A 15M-particle
// diffuse cache is 170 MB a frame: written through the page cache, the kernel's copy and its upkeep
// took about a tenth of the diffuse stage's processor time, and read through it, a frame costs more
// when the cache no longer holds it. Direct, it costs the same whatever the cache holds. File systems
// that refuse direct I/O (at open or at the first transfer) are read and written through the page
// cache.
#include <cstddef>
#include <filesystem>
#include <string>

namespace spume {

// Reads exactly `size` bytes from the start of `path` into data. Throws Error naming the file when it
// cannot be opened or holds fewer bytes.
void read_file_bytes(const std::filesystem::path& path, char* data, size_t size);

// Creates (or truncates) `path` and writes [data, data + size) to it. Throws Error starting with
// `where` when it cannot (the file may then hold part of the bytes).
void write_file_bytes(const std::filesystem::path& path, const char* data, size_t size, const std::string& where);

}  // namespace spume

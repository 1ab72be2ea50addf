#pragma once
// Outputs are written to a temporary file beside the target and renamed into place, so a crash or an
// error never leaves a half-written file under the final name.
#include <filesystem>
#include <functional>
#include <ostream>

namespace spume {

// Calls write(stream) on a temporary file next to `path` (`path.tmp.<host>.<pid>`, so processes on
// several hosts sharing a folder never collide), flushes, then renames it over `path`.
// Throws Error naming the path if anything fails; the temporary file is removed on failure.
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

// The same for `size` bytes in memory, written by write_file_bytes (core/direct_io.h): their whole
// 4 KiB blocks go to the disk directly when `data` is 4 KiB aligned.
void write_bytes_atomically(const std::filesystem::path& path, const char* data, size_t size);

// Removes the temporary files in `dir` (not below it) that writers on this host left when they died
// (their pid no longer runs). Files of live processes and of other hosts are kept. Returns how many.
int remove_dead_temporaries(const std::filesystem::path& dir);

}  // namespace spume

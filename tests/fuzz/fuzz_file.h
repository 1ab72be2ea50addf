#pragma once
// The readers take paths: each fuzz input is written to one scratch file per process (libFuzzer runs
// inputs one at a time), read, and removed. Bad input must end in spume::Error; anything else (a
// crash, a sanitizer report, another exception, a hang, a huge allocation) is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "sim/core/error.h"

namespace spume::fuzz {

inline std::filesystem::path scratch_file(const char* extension) {
  return std::filesystem::temp_directory_path() /
         ("spume_fuzz_" + std::to_string(::getpid()) + extension);
}

inline void write_input(const std::filesystem::path& path, const uint8_t* data, size_t size) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) spume::fail(path.string(), ": cannot write the fuzz scratch file");
  if (size) std::fwrite(data, 1, size, f);
  std::fclose(f);
}

// Runs fn(), accepting a spume::Error (bad input, reported as it should be).
template <typename Fn>
void expect_clean(Fn&& fn) {
  try {
    fn();
  } catch (const spume::Error&) {
  }
}

// Writes the input to a scratch file with `extension` and calls read(path) on it.
template <typename Read>
int read_as_file(const uint8_t* data, size_t size, const char* extension, Read&& read) {
  const std::filesystem::path path = scratch_file(extension);
  write_input(path, data, size);
  read(path);
  std::filesystem::remove(path);
  return 0;
}

}  // namespace spume::fuzz

#pragma once
// Big-endian byte building for the particle I/O tests' hand-made files (BGEO, VTK, PLY headers).
#include <cstring>
#include <string>

namespace spume::io_test {

// Appends v's bytes in big-endian order (the test machine is little-endian).
template <typename T>
void be(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (size_t i = 0; i < sizeof(T); ++i) out += b[sizeof(T) - 1 - i];
}

}  // namespace spume::io_test

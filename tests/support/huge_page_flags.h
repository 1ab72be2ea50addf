#pragma once
// What the kernel says of a mapping's huge pages: its "hg" flag (advised MADV_HUGEPAGE) in
// /proc/self/smaps, for tests that check advice against the kernel's account rather than the code.
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

namespace spume::testing {

inline bool kernel_has_huge_pages() { return std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled").good(); }

// The VmFlags line of the mapping that holds address `a`; empty when no mapping holds it.
inline std::string vm_flags_at(const void* a) {
  const uintptr_t x = reinterpret_cast<uintptr_t>(a);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= x && x < end;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line;
    }
  }
  return {};
}

inline bool advised(const void* a) { return vm_flags_at(a).find(" hg") != std::string::npos; }

}  // namespace spume::testing

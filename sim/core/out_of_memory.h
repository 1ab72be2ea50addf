#pragma once
// Running out of memory, said as an Error: what was being allocated, how much, and what the process
// had, instead of "internal error: std::bad_alloc". Allocations sized by an input (a file's bytes, a
// decompressed stream) are wrapped where they happen (allocating); the file and frame boundaries
// (read_fluid_file, the diffuse simulator's and the renderer's frames) say which file or frame it was.
#include <cstdint>
#include <string>
#include <string_view>
#include <new>
#include <utility>

#include "sim/core/error.h"

namespace spume {

// "out of memory <what> (1.5 GiB)", e.g. what = "allocating the file's bytes", followed by what the
// process had: its address space in use against its limit (ulimit -v), or the memory the system had
// available. `bytes` 0: the size of the last allocation that failed, when one was recorded
// (record_failed_allocation), else none.
std::string out_of_memory_message(std::string_view what, uint64_t bytes = 0);

// What the process had: "; the process had 300 MiB of address space, its limit (ulimit -v) is 293 MiB",
// or (without a limit) its resident memory and what the system had available; "" when unknown.
std::string memory_situation();

// Called by spume's allocators when they fail, so that a bad_alloc caught far from where it was
// thrown can still say how much was asked for.
void record_failed_allocation(uint64_t bytes);

// "2.0 GiB", "300 MiB", "12 KiB", "17 bytes".
std::string byte_size_text(uint64_t bytes);

// Runs fn; a std::bad_alloc inside it becomes an Error: out_of_memory_message(what, bytes).
template <typename Fn>
decltype(auto) allocating(std::string_view what, uint64_t bytes, Fn&& fn) {
  try {
    return std::forward<Fn>(fn)();
  } catch (const std::bad_alloc&) {
    throw Error(out_of_memory_message(what, bytes));
  }
}

}  // namespace spume

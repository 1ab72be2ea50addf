#pragma once
// Reading a file that may be damaged or hostile without risking the process that reads it. OpenVDB
// trusts the lengths inside a file (a flipped bit in a string's size makes it allocate and clear
// gigabytes, entry after entry) and Debian's build keeps its assertions (a damaged page header calls
// abort()). So a process that opts in (the spume command) first reads each such file in a child: its
// own executable, started as `EXE __read-check FORMAT FILE [GRID]`, with an address-space limit and an
// alarm. Only a file the child read cleanly is read in-process; otherwise the error names the file and
// what happened to the child. No allocation function or signal handler is replaced anywhere: a
// library user that does not opt in reads in-process, as the fuzzers do.
#include <cstdint>
#include <filesystem>
#include <string>

namespace spume {

// The word that starts the child: `EXE __read-check FORMAT FILE GRID` (render/app/read_check_command.h).
inline constexpr const char* kReadCheckWord = "__read-check";

// Reads of untrusted files are checked in a child running `helper` (the spume command passes its own
// executable). Call once, before any read.
void contain_untrusted_reads(const std::filesystem::path& helper);

// When containment is on, runs the child on `path` (once per file version: a file whose size and
// modification time are unchanged is not checked again) and returns when it read the file cleanly; else
// throws an Error naming the file. `format`: the reader, "vdb". Without containment, returns at once.
void check_read_in_child(const std::filesystem::path& path, const std::string& format, const std::string& grid_name);

// What a sound file can make a reader allocate: its bytes decompressed (Blosc rarely shrinks
// particles 64-fold) and a margin. The child's address-space limit is what it had plus this.
uint64_t contained_read_budget(uint64_t file_bytes);

// The child's limits, set on itself by the __read-check command before it reads: an alarm that ends
// it after `seconds`, and its address space to what it has now plus `budget_bytes` when that is below
// the limit it has. Not under AddressSanitizer, which reserves terabytes up front: the parent caps
// single allocations through ASAN_OPTIONS instead. read_budget_in_force() is then the budget, for the
// reader's message (else 0).
void limit_this_process_for_a_contained_read(uint64_t budget_bytes, unsigned seconds);
uint64_t read_budget_in_force();

// How long a child may take on a file of `file_bytes` (a sound one reads at well over 50 MB/s).
unsigned contained_read_seconds(uint64_t file_bytes);

}  // namespace spume

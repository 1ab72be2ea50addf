#pragma once
// Whether this build runs under AddressSanitizer (GCC's and clang's spellings), for the few places
// whose behaviour it changes: it reserves terabytes of address space at start, so no address-space
// limit (ulimit -v, RLIMIT_AS) can be set on a process that runs it, and it brings its own allocator.
#if defined(__SANITIZE_ADDRESS__)
#define SPUME_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SPUME_ADDRESS_SANITIZER 1
#endif
#endif
#ifndef SPUME_ADDRESS_SANITIZER
#define SPUME_ADDRESS_SANITIZER 0
#endif

namespace spume {

inline constexpr bool kAddressSanitizer = SPUME_ADDRESS_SANITIZER;

}  // namespace spume

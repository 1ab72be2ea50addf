#pragma once
// A function built for several instruction sets and picked when the program loads (GCC's and clang's
// target_clones), for the hot loops whose results do not depend on the choice (no FMA contraction).
// Clang 14 does not honour an "arch=" entry: it ran the x86-64-v4 (AVX-512) clone on a CPU without
// AVX-512. Under clang only AVX2 and the baseline are built.
#if defined(__clang__)
#define SPUME_CLONES_FOR_AVX512_AND_AVX2 __attribute__((target_clones("avx2", "default")))
#else
#define SPUME_CLONES_FOR_AVX512_AND_AVX2 __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#endif

#pragma once
// CURVETET_WIDE_VECTORS before a function: on x86-64 with GCC it also gets
// an AVX2 version, chosen at load time. AVX2 alone brings no FMA, so a
// function that keeps its order of operations gives the same bits in both.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define CURVETET_WIDE_VECTORS __attribute__((target_clones("avx2", "default")))
#else
#define CURVETET_WIDE_VECTORS
#endif

// HEXCAL_VECTOR_CLONES: a hot loop that vectorises along the candidates, built
// for AVX-512 and AVX2 besides the baseline x86-64 the project targets; the
// loader picks the widest clone the processor has (GCC's target_clones, an
// ifunc). Lanes are independent candidates and the files that use it are
// built with -ffp-contract=off, so every clone rounds as the baseline does and
// a plan does not depend on the processor (docs/performance.md, "Vector clones").
#pragma once

// Not under the sanitizers: their runtime is not set up when the loader runs
// an ifunc resolver, and the baseline loop is what they need to see.
#if defined(__SANITIZE_ADDRESS__)
#define HEXCAL_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HEXCAL_SANITIZED 1
#endif
#endif

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(HEXCAL_SANITIZED)
#define HEXCAL_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define HEXCAL_VECTOR_CLONES
#endif

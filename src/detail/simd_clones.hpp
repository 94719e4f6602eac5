#pragma once
// ADJOIN_SIMD_CLONES before a function definition compiles it twice, for the baseline x86-64
// and for x86-64-v3 (AVX2, FMA), and picks one at load time by the processor (GCC's
// target_clones, as FFTW picks its own SIMD kernels). Elsewhere it expands to nothing, and
// also under ThreadSanitizer, whose instrumented ifunc resolvers would run before its runtime
// is up (the program crashes while loading).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(__SANITIZE_THREAD__)
#define ADJOIN_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define ADJOIN_SIMD_CLONES
#endif

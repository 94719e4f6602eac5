#pragma once
// One kernel body, two builds of it: a baseline (x86-64 SSE2) and an AVX2 one, the latter chosen
// at run time where the processor has it. Both run the same operations in the same order, so a
// result does not depend on the machine (no fused multiply-adds: the target adds only the wider
// lanes). Used by the structure step's kernels (step_kernels.cpp) and the bilinear passes
// (bilinear_lanes.cpp), each a table of function pointers filled by ADJOIN_KERNEL.

#define ADJOIN_INLINE [[gnu::always_inline]] inline

// ADJOIN_KERNEL(ret, name, (params), (args)) defines name_base (and name_avx2 where the compiler
// can build it) calling name_body(args), which must be an ADJOIN_INLINE function.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define ADJOIN_KERNEL(ret, name, params, args)        \
  ret name##_base params { return name##_body args; } \
  __attribute__((target("avx2"))) ret name##_avx2 params { return name##_body args; }
#define ADJOIN_HAVE_AVX2 1
#else
#define ADJOIN_KERNEL(ret, name, params, args) \
  ret name##_base params { return name##_body args; }
#endif

namespace adjoin::detail {

// The AVX2 table where the processor has AVX2 (and the AVX2 kernels were built), else the
// baseline one. Call it once and keep the answer (a function-local static).
template <class Kernels>
const Kernels& kernels_for_this_cpu(const Kernels& baseline, [[maybe_unused]] const Kernels* avx2) {
#ifdef ADJOIN_HAVE_AVX2
  if (avx2 != nullptr && __builtin_cpu_supports("avx2")) return *avx2;
#endif
  return baseline;
}

}  // namespace adjoin::detail

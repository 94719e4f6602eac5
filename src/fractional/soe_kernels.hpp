#pragma once
// The arithmetic shared by SoeHistory (soe_history.cpp) and SoeBank (soe_bank.cpp), so that a
// bank member's lag sums equal a SoeHistory's bit for bit (tests/test_soe_bank.cpp).
//
// Modes ahead. The modes' input at step m is y_{m-n0} (and y_{m-n0-1}), n0 steps old, so when
// step m is taken the inputs of steps m..m+kAhead-1 are already known (kAhead <= n0): each mode
// is advanced kAhead steps at once, its state held in a register, and the far sums
// F_k = sum_q s_q(m + k) of those steps are accumulated together. The states are then loaded and
// stored once per kAhead steps instead of every step (40 members at Q = 70 are 22 kB of states,
// which did not stay in L1 beside the values' lines: the bank was bound by that traffic).
//
// Per mode and step (the same expression, so the same contractions to fused multiply-adds, in
// both engines):
//     one-term:  s <- (s - d s) + g y                     (d = 1 - lambda to full precision)
//     two-term:  s <- ((r y' + p y) + b s'') + a s'       (y' = the input before y)
// The far sum of a step adds the modes in four interleaved partial sums, mode q into sum q % 4
// in increasing q, combined as (S0 + S1) + (S2 + S3); one- and two-term modes apart, their sums
// added. SoeHistory holds the four partial sums in the lanes of one vector (its lanes are four
// modes), SoeBank in four passes over the modes (its lanes are four members).
//
// The window: sum_{j=1}^{n0-1} w_j y_{m-j} = [sum over i < n0 of y_{m-n0-1+i} v_i] + w_1 y_{m-1},
// v = SoeCompression::near_shifted (0, 0, w_{n0-1}, ..., w_2), in four partial sums (i % 4)
// combined as (S0 + S1) + (S2 + S3); the lag sum is
// (F + window) + w_1 y_{m-1}: the newest value enters last, one fused multiply-add from the
// result (the caller's next value usually depends on this lag sum).
//
// GCC vector extensions: AVX2 registers in the x86-64-v3 clone (ADJOIN_SIMD_CLONES), pairs of
// SSE2 registers otherwise. GCC warns that returning these vectors by value has another ABI
// with and without AVX (and notes it for parameters: the helpers take references); they only
// pass between the inlined helpers here.
#pragma GCC diagnostic ignored "-Wpsabi"

#include <cstddef>
#include <cstring>

namespace adjoin::soe_detail {

using V4 = double __attribute__((vector_size(32)));

// Steps whose far sums are made at once (<= n0).
constexpr std::size_t kAhead = 4;

[[gnu::always_inline]] inline V4 load(const double* p) {
  V4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store(double* p, const V4& v) { std::memcpy(p, &v, sizeof v); }
[[gnu::always_inline]] inline V4 splat(double x) { return V4{x, x, x, x}; }

// One-term mode, one step.
[[gnu::always_inline]] inline V4 single_step(const V4& s, const V4& d, const V4& g, const V4& y) {
  return (s - d * s) + g * y;
}
// Two-term mode, one step (s1: the last state, s2: the one before).
[[gnu::always_inline]] inline V4 paired_step(const V4& s1, const V4& s2, const V4& a, const V4& b, const V4& p,
                                             const V4& r, const V4& y, const V4& y_before) {
  return ((r * y_before + p * y) + b * s2) + a * s1;
}

}  // namespace adjoin::soe_detail

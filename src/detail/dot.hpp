#pragma once
// Dot products for the history sums, with several independent partial sums: one chain of
// additions would wait on each addition's latency, these keep the vector units busy. Compiled
// also for AVX2 + FMA and chosen at load time where the processor has them (results then
// differ from the baseline build's by rounding only).
#include <cstddef>

namespace adjoin::detail {

// sum_{i<n} a[i] b[i].
double dot(const double* __restrict a, const double* __restrict b, std::size_t n);
// sum_{q<n} y[q] w[-q]: a convolution term with the weights read backwards.
double dot_reversed(const double* __restrict y, const double* __restrict w, std::size_t n);

}  // namespace adjoin::detail

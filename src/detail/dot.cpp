#include "dot.hpp"
#include "simd_clones.hpp"

namespace adjoin::detail {


// sum_{i<n} a[i] b[i], with sixteen independent partial sums: the compiler keeps them in four
// AVX2 registers, four chains of fused multiply-adds (eight sums made two chains, sixteen deep
// for the fft history's 128-lag window, whose latency set the pace; the weak scene's fft run
// went from 1.06 to 0.91 of 7307fe9's time, docs/explanation/benchmarks.md).
ADJOIN_SIMD_CLONES
double dot(const double* __restrict a, const double* __restrict b, std::size_t n) {
  double s[16] = {};
  std::size_t i = 0;
  for (; i + 16 <= n; i += 16)
    for (std::size_t k = 0; k < 16; ++k) s[k] += a[i + k] * b[i + k];
  double tail = 0.0;
  for (; i < n; ++i) tail += a[i] * b[i];
  const double lo = ((s[0] + s[8]) + (s[1] + s[9])) + ((s[2] + s[10]) + (s[3] + s[11]));
  const double hi = ((s[4] + s[12]) + (s[5] + s[13])) + ((s[6] + s[14]) + (s[7] + s[15]));
  return (lo + hi) + tail;
}

// sum_{q<n} y[q] w[-q]: a convolution term with the weights read backwards (four partial
// sums: with eight, the reversed loads, not the additions, set the pace).
ADJOIN_SIMD_CLONES
double dot_reversed(const double* __restrict y, const double* __restrict w, std::size_t n) {
  double s[4] = {};
  std::size_t q = 0;
  for (; q + 4 <= n; q += 4)
    for (std::size_t k = 0; k < 4; ++k) s[k] += y[q + k] * w[-static_cast<std::ptrdiff_t>(q + k)];
  for (; q < n; ++q) s[0] += y[q] * w[-static_cast<std::ptrdiff_t>(q)];
  return (s[0] + s[1]) + (s[2] + s[3]);
}

}  // namespace adjoin::detail

#include "dot.hpp"
#include "simd_clones.hpp"

namespace adjoin::detail {


// sum_{i<n} a[i] b[i], with eight independent partial sums (the compiler keeps them in vector
// registers; one chain of additions would be latency-bound).
ADJOIN_SIMD_CLONES
double dot(const double* __restrict a, const double* __restrict b, std::size_t n) {
  double s[8] = {};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (std::size_t k = 0; k < 8; ++k) s[k] += a[i + k] * b[i + k];
  for (; i < n; ++i) s[0] += a[i] * b[i];
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
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

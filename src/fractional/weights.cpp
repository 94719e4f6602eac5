#include "adjoin/fractional/weights.hpp"

namespace adjoin {

std::vector<double> grunwald_letnikov_weights(double order, std::size_t count) {
  std::vector<double> w(count);
  if (count == 0) return w;
  w[0] = 1.0;
  for (std::size_t j = 1; j < count; ++j)
    w[j] = (1.0 - (order + 1.0) / static_cast<double>(j)) * w[j - 1];
  return w;
}

}  // namespace adjoin

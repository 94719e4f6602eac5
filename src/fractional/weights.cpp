#include "adjoin/fractional/weights.hpp"

#include <cmath>

namespace adjoin {

std::vector<double> grunwald_letnikov_weights(double order, std::size_t count) {
  std::vector<double> w(count);
  if (count == 0) return w;
  w[0] = 1.0;
  for (std::size_t j = 1; j < count; ++j)
    w[j] = (1.0 - (order + 1.0) / static_cast<double>(j)) * w[j - 1];
  return w;
}

std::vector<double> bdf2_weights(double order, std::size_t count) {
  // P(zeta) = p0 + p1 zeta + p2 zeta^2; a_n = 1/(n p0) sum_{k=1}^{min(n,2)} ((order+1) k - n) p_k a_{n-k}.
  const double p[3] = {1.5, -2.0, 0.5};
  std::vector<double> w(count);
  if (count == 0) return w;
  w[0] = std::pow(p[0], order);
  for (std::size_t n = 1; n < count; ++n) {
    const double dn = static_cast<double>(n);
    double s = ((order + 1.0) - dn) * p[1] * w[n - 1];
    if (n >= 2) s += ((order + 1.0) * 2.0 - dn) * p[2] * w[n - 2];
    w[n] = s / (dn * p[0]);
  }
  return w;
}

std::vector<double> convolution_weights(WeightRule rule, double order, std::size_t count) {
  return rule == WeightRule::bdf2 ? bdf2_weights(order, count) : grunwald_letnikov_weights(order, count);
}

}  // namespace adjoin

#include "adjoin/fractional/direct_history.hpp"

#include <stdexcept>

namespace adjoin {

DirectHistory::DirectHistory(std::vector<double> weights) : w_(std::move(weights)) {
  y_.reserve(w_.empty() ? 0 : w_.size() - 1);
}

void DirectHistory::push(double y) {
  if (y_.size() >= w_.size())
    throw std::logic_error("DirectHistory: more values pushed than weights were given");
  y_.push_back(y);
  // Next step m = size(): sum_{j=1}^{m} w_j y_{m-j}. Unused past the last weight.
  const std::size_t m = y_.size();
  if (m >= w_.size()) { lag_sum_ = 0.0; return; }
  double s = 0.0;
  const double* yp = y_.data() + m - 1;  // y_{m-1}
  for (std::size_t j = 1; j <= m; ++j) s += w_[j] * yp[1 - static_cast<std::ptrdiff_t>(j)];
  lag_sum_ = s;
}

std::size_t DirectHistory::bytes() const {
  return sizeof(*this) + (w_.capacity() + y_.capacity()) * sizeof(double);
}

}  // namespace adjoin

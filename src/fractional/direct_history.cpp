#include "adjoin/fractional/direct_history.hpp"

#include <stdexcept>

#include "../detail/dot.hpp"

namespace adjoin {

DirectHistory::DirectHistory(std::vector<double> weights)
    : w_(std::move(weights)), y_(w_.empty() ? 0 : w_.size() - 1, 0.0) {}

double DirectHistory::push(double y) {
  if (size_ >= w_.size())
    throw std::logic_error("DirectHistory: more values pushed than weights were given");
  // Next step m = size(): sum_{j=1}^{m} w_j y_{m-j}. Unused past the last weight.
  const std::size_t m = ++size_;
  if (m >= w_.size()) return lag_sum_ = 0.0;
  y_[m - 1] = y;
  // y_q w_{m-q} for q = 0 .. m-1 (partial sums in vector registers: detail/dot.hpp).
  return lag_sum_ = detail::dot_reversed(y_.data(), w_.data() + m, m);
}

std::size_t DirectHistory::bytes() const {
  return sizeof(*this) + (w_.capacity() + y_.capacity()) * sizeof(double);
}

}  // namespace adjoin

#include "adjoin/fractional/direct_history.hpp"

#include <algorithm>
#include <new>
#include <stdexcept>

#include "../detail/dot.hpp"

namespace adjoin {

DirectHistory::Buffer DirectHistory::aligned_buffer(std::size_t count) {
  constexpr std::size_t kAlign = 64;
  const std::size_t bytes = (std::max<std::size_t>(count, 1) * sizeof(double) + kAlign - 1) / kAlign * kAlign;
  auto* p = static_cast<double*>(std::aligned_alloc(kAlign, bytes));
  if (p == nullptr) throw std::bad_alloc();
  return Buffer(p);
}

DirectHistory::DirectHistory(std::vector<double> weights)
    : count_(weights.size()), w_(aligned_buffer(weights.size())), y_(aligned_buffer(weights.size())) {
  std::copy(weights.begin(), weights.end(), w_.get());
}

void DirectHistory::push(double y) {
  if (size_ >= count_) throw std::logic_error("DirectHistory: more values pushed than weights were given");
  y_[size_++] = y;
  // Next step m = size(): sum_{j=1}^{m} w_j y_{m-j}. Unused past the last weight.
  const std::size_t m = size_;
  if (m >= count_) { lag_sum_ = 0.0; return; }
  // y_q w_{m-q} for q = 0 .. m-1 (partial sums in vector registers: detail/dot.hpp).
  lag_sum_ = detail::dot_reversed(y_.get(), w_.get() + m, m);
}

std::size_t DirectHistory::bytes() const { return sizeof(*this) + 2 * count_ * sizeof(double); }

}  // namespace adjoin

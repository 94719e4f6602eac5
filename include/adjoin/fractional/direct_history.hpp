#pragma once
// The direct O(N^2) history engine: each lag sum computed as written. See history.hpp.
#include <cstdlib>
#include <memory>

#include "adjoin/fractional/history.hpp"

namespace adjoin {

class DirectHistory final : public ConvolutionHistory {
 public:
  explicit DirectHistory(std::vector<double> weights);
  double lag_sum() const override { return lag_sum_; }
  void push(double y) override;
  std::size_t size() const override { return size_; }
  std::size_t bytes() const override;

 private:
  // The weights and the values on 64-byte boundaries: each step's sum reads both whole, and
  // where a vector's start falls against the cache lines moved its time by 10 % from one
  // allocation to the next. (The sums are formed by index, so they do not depend on it.)
  struct Free {
    void operator()(double* p) const { std::free(p); }
  };
  using Buffer = std::unique_ptr<double[], Free>;
  static Buffer aligned_buffer(std::size_t count);

  std::size_t count_ = 0;  // weights w_0..w_{count-1}; at most count values
  std::size_t size_ = 0;   // values pushed
  Buffer w_, y_;
  double lag_sum_ = 0.0;
};

}  // namespace adjoin

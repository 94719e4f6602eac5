#pragma once
// The direct O(N^2) history engine: each lag sum computed as written. See history.hpp.
#include "adjoin/fractional/history.hpp"

namespace adjoin {

class DirectHistory final : public ConvolutionHistory {
 public:
  explicit DirectHistory(std::vector<double> weights);
  double lag_sum() const override { return lag_sum_; }
  double push(double y) override;
  std::size_t size() const override { return size_; }
  std::size_t bytes() const override;

 private:
  std::vector<double> w_;
  // y_0..y_{N-1}, allocated at construction and written by index (y_N, the last value
  // accepted, enters no lag sum and is not kept). Not push_back: its reallocation path, never
  // taken, made every push save and restore six registers (a fifth of a two-block step's
  // history glue).
  std::vector<double> y_;
  std::size_t size_ = 0;  // values pushed
  double lag_sum_ = 0.0;
};

}  // namespace adjoin

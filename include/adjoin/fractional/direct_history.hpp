#pragma once
// The direct O(N^2) history engine: each lag sum computed as written. See history.hpp.
#include "adjoin/fractional/history.hpp"

namespace adjoin {

class DirectHistory final : public ConvolutionHistory {
 public:
  explicit DirectHistory(std::vector<double> weights);
  double lag_sum() const override { return lag_sum_; }
  void push(double y) override;
  std::size_t size() const override { return y_.size(); }
  std::size_t bytes() const override;

 private:
  std::vector<double> w_;
  std::vector<double> y_;
  double lag_sum_ = 0.0;
};

}  // namespace adjoin

#pragma once
// History sums: the non-local part of a discrete fractional derivative.
//
// A ConvolutionHistory holds a sequence y_0, y_1, ... pushed one value per time step and the
// weights w_0..w_N of a convolution quadrature. After y_0..y_{m-1} have been pushed,
//
//     lag_sum() = sum_{j=1}^{m} w_j y_{m-j}
//
// is the part of step m's convolution that does not involve the still unknown y_m; a scheme
// adds w_0 y_m itself (implicitly or explicitly). At most N + 1 values (y_0..y_N) may be
// pushed; lag sums past step N are zero.
//
// Engines:
//  - direct: the sum as written, O(m) per step, O(N^2) in all. The reference.
//  - fft: blocked FFT convolution after Hairer, Lubich and Schlichte (1985): the same sums,
//    O(N log^2 N) in all and O(N) memory, equal to direct to rounding.
//  - soe: a direct window of the first lags and a sum of exponentials beyond it
//    (soe_history.hpp): O(1) work and memory per step, the weights within a stated relative
//    error (the tolerance, 1e-12 by default) of the exact ones.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "adjoin/core/history_engine.hpp"
#include "adjoin/fractional/weights.hpp"

namespace adjoin {

class ConvolutionHistory {
 public:
  virtual ~ConvolutionHistory() = default;
  // sum_{j=1}^{m} w_j y_{m-j} with m = size().
  virtual double lag_sum() const = 0;
  // Appends y_m (m = size()) and prepares the next lag sum, which it returns (lag_sum() from
  // now on: a caller that pushes and then reads the sum, HistorySet, saves a virtual call).
  virtual double push(double y) = 0;
  virtual std::size_t size() const = 0;
  // Bytes held by the engine (for the memory benchmarks).
  virtual std::size_t bytes() const = 0;
  // The largest relative error of the weights the engine applies (0: exact to rounding), and
  // the number of recurrences it steps per value (0 for the engines that keep the past).
  virtual double weight_error() const { return 0.0; }
  virtual std::size_t modes() const { return 0; }
};

// `weights` holds w_0..w_N; the history accepts N + 1 pushes.
// (direct and fft only: soe needs to know the rule, below.)
std::unique_ptr<ConvolutionHistory> make_history(HistoryEngine engine, std::vector<double> weights);

// A history for the weights w_0..w_{count-1} of `rule` at `order`; `tolerance` is soe's
// relative weight error (the others are exact). soe needs 0 < order < 1 and a tolerance in
// [1e-15, 1).
std::unique_ptr<ConvolutionHistory> make_history(HistoryEngine engine, WeightRule rule, double order, std::size_t count,
                                                 double tolerance);

}  // namespace adjoin

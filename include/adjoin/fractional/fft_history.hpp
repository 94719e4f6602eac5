#pragma once
// The fast history engine: the lag sums of DirectHistory (see history.hpp), equal to them to
// rounding, in O(N log^2 N) time and O(N) memory for N + 1 steps.
//
// Method (blocked "online" convolution after Hairer, Lubich and Schlichte, SIAM J. Sci. Stat.
// Comput. 6 (1985) 532-541): split every product w_j y_i by the lag j.
//  - Near lags 1 <= j < B are summed directly at every step (B = near_lags(), a few dozen:
//    below that size a dot product beats an FFT).
//  - Far lags j in [L, 2L), L = B, 2B, 4B, ..., pair with the aligned block of L values of y
//    that contains i. Such a block y_{kL}..y_{kL+L-1} is complete after step m = (k+1)L, and
//    its products with w_L..w_{2L-1} only feed steps n >= m; so at that moment one FFT
//    convolution of length 2L adds them to an accumulator of future lag sums. Each (i, j)
//    with j >= B belongs to exactly one such tile.
// Per level there are N/L tiles costing O(L log L) each, hence O(N log N) per level and
// O(N log^2 N) in all. The spectra of the weight segments are computed once, in the
// constructor; tiles whose few remaining outputs are cheaper to form directly are.
//
// FFTW plans are created once per transform length per process (under a global mutex, since
// FFTW's planner is not thread-safe, with FFTW_ESTIMATE) and shared by all instances;
// executing them is thread-safe, so independent histories may run in parallel threads. One
// instance must not be used from two threads at once.
#include <cstddef>
#include <memory>
#include <vector>

#include "adjoin/fractional/history.hpp"

namespace adjoin {

class FftHistory final : public ConvolutionHistory {
 public:
  // `weights` holds w_0..w_N; the history accepts N + 1 pushes (more throw std::logic_error).
  explicit FftHistory(std::vector<double> weights);
  ~FftHistory() override;
  FftHistory(const FftHistory&) = delete;
  FftHistory& operator=(const FftHistory&) = delete;

  double lag_sum() const override { return lag_sum_; }
  void push(double y) override;
  std::size_t size() const override { return y_.size(); }
  std::size_t bytes() const override;

  // Lags below this are summed directly each step.
  static constexpr std::size_t near_lags() { return kNear; }

 private:
  static constexpr std::size_t kNear = 64;
  struct Spectra;  // FFTW buffers and the weight spectra, per level

  void add_tile(std::size_t level, std::size_t m);

  std::vector<double> w_;       // w_0..w_N
  std::vector<double> near_;    // w_{B-1}, ..., w_1: reversed so the near sum runs forwards
  std::vector<double> y_;       // y_0..y_{m-1}
  std::vector<double> future_;  // future_[n]: far-lag part of step n's lag sum, so far
  std::unique_ptr<Spectra> spectra_;
  double lag_sum_ = 0.0;
};

}  // namespace adjoin

#pragma once
// The fast history engine: the lag sums of DirectHistory (see history.hpp), equal to them to
// rounding, in O(N log^2 N) time and O(N) memory for N + 1 steps.
//
// Method (blocked "online" convolution after Hairer, Lubich and Schlichte, SIAM J. Sci. Stat.
// Comput. 6 (1985) 532-541, with levels that grow by a factor r instead of 2): split every
// product w_j y_i by the lag j.
//  - Near lags 1 <= j < B are summed directly at every step (B = near_lags(): below that a
//    vectorised dot product beats an FFT).
//  - Level L = B, rB, r^2 B, ... takes the lags j in [L, rL), split into the partitions
//    [pL, pL + L), p = 1..r-1. The tile (y block k' = y_{k'L}..y_{k'L+L-1}, partition p) has
//    products that land on steps n >= (k'+p) L only, so all tiles with k' + p = k + 1 are
//    added together when y block k is complete, at step m = (k+1) L: one "window" of
//    length 2L. Its spectrum is sum_p X_{k+1-p} W_p, with the spectra X of the last r-1
//    y blocks kept and the weight spectra W_p made once; one inverse FFT adds it to an
//    accumulator of future lag sums. Each (i, j) with j >= B belongs to exactly one tile.
// A level costs one forward and one inverse FFT of length 2L per L steps, O(N log N) in all,
// and there are log_r(N/B) levels, so a larger r means fewer transforms for more (cheap)
// spectrum products; r = 2 is the original scheme. Spectra are made on first use. The last
// window or two of a level want fewer outputs (steps past N are never read): by a cost
// estimate they are formed directly, or by a shorter FFT of just the values that reach
// those outputs, or as usual. Memory: w, y and the accumulator (3 doubles a step) plus
// about 4 to 5 doubles a step of spectra.
//
// FFTW plans are created once per transform length per process, when a window first needs
// them (under a global mutex, since FFTW's planner is not thread-safe, with FFTW_ESTIMATE and
// FFTW_NO_BUFFERING: planning is most of a short run's cost) and shared by all instances;
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
  double push(double y) override;
  std::size_t size() const override { return y_.size(); }
  std::size_t bytes() const override;

  // Lags below this are summed directly each step.
  static constexpr std::size_t near_lags() { return kNear; }
  // The block length grows by this factor from one level to the next (B, rB, r^2 B, ...).
  static constexpr std::size_t level_ratio() { return kRatio; }

 private:
  // B = 128, r = 8: among the fastest of B in {64, 128, 256} x r in {2, 4, 8, 16} measured
  // (r = 2 was about 1.5 times slower; at r = 16 the spectrum products start to dominate).
  static constexpr std::size_t kNear = 128;  // B
  static constexpr std::size_t kRatio = 8;   // r: each level's blocks are r times the last's
  struct Spectra;  // FFTW buffers, the weight and y block spectra, per level

  void add_window(std::size_t level, std::size_t m);

  std::vector<double> w_;       // w_0..w_N
  std::vector<double> near_;    // 0, w_{B-1}, ..., w_1: reversed so the near sum runs forwards
  std::vector<double> y_;       // y_0..y_{m-1}
  std::vector<double> future_;  // future_[n]: far-lag part of step n's lag sum, so far
  std::unique_ptr<Spectra> spectra_;
  double lag_sum_ = 0.0;
};

}  // namespace adjoin

#pragma once
// The constant-memory history engine ("soe", sum of exponentials): the lag sums of
// DirectHistory (history.hpp) for the Grünwald–Letnikov and BDF2 weights, up to a stated
// relative error of the weights, in O(Q + n0) work and memory per step, whatever the length.
//
// Method. The weights are the coefficients of delta(zeta)^order, 0 < order < 1, with
// delta = 1 - zeta (Grünwald–Letnikov) or 3/2 - 2 zeta + zeta^2 / 2 (BDF2). From
// s^a = (sin(pi a)/pi) int_0^inf x^(a-1) s/(s + x) dx (the real-axis representation used by
// Banjai & López-Fernández, Numer. Math. 141 (2019), and by Guo, Zeng, Turner, Burrage &
// Karniadakis, SISC 41 (2019), "fast method II"),
//
//     w_n = -(sin(pi a)/pi) int_0^inf x^a e_n(x) dx,   n >= 1,
//
// where e_n(x) are the coefficients of 1/(delta(zeta) + x): (1 + x)^(-n-1) for GL, and for
// BDF2 a sequence with e_n = (2 e_{n-1} - e_{n-2}/2)/(3/2 + x): a two-term recurrence whose
// roots lie inside the unit disc. A quadrature of the integral with nodes x_q and weights
// C_q makes w_n ~ sum_q C_q e_n(x_q) for n in [n0, N]: each node is one (or, for BDF2 at
// small x, two) geometric sequence(s), so the part of the lag sum with lags j >= n0 is
// carried by Q recurrences updated once per step, and lags 1..n0-1 are summed directly.
//
// Quadrature: the trapezoidal rule in u with x = exp(u - exp(-(u - u_c))) (exponential
// grading towards large x, double-exponential decay below x_c = e^{u_c} = 0.1 / N, where
// every e_n with n <= N is nearly constant): for each n the integrand is analytic in a strip
// about the real u axis and the rule converges geometrically, uniformly in n in relative
// terms. The step and the ends of the range follow from the tolerance; the compression is
// then VERIFIED against the exact weights (long double: Miller's recurrence at every n up to
// 1024, Stirling's series for the Gamma ratio at 64 n per octave beyond, up to N), the step
// is refined until the largest relative error is within the tolerance, and that largest
// error is reported as the bound (SoeCompression::error; sampled, so a bound in practice:
// tests/test_soe_history.cpp checks it at every lag below 8192). At 1e-12 and N = 2^24:
// Q = 77 to 82 recurrences for orders 0.05 to 0.95, errors up to 9.2e-13 (the step is the
// coarsest of a few tried that verifies), 5M to 10M instructions to make (one or two tries).
// Lags 1..n0-1 (n0 = 32) use the exact weights: the window keeps the right tail of the
// integral (large x, where e_n decays like x^(-n/2)) short.
//
// Precision: a mode whose decay 1 - lambda is tiny (x ~ 1/N) is stored and stepped as
// s <- (s - d s) + g y with d = 1 - lambda held to full relative precision, so its effective
// decay over N steps is exact to rounding (lambda itself in a double would be off by N eps).
// BDF2 nodes with x < 0.3 are split into their two real geometric modes for that reason;
// larger x keep the two-term real recurrence (|lambda| < 0.8 there).
//
// The compression depends on (rule, order, tolerance) and N only: the weights are dimensionless
// (the step h enters the scheme as h^-order outside them). It is made for a design length N,
// the run's number of steps rounded up to a power of two (at least 2^10): once per process
// and (rule, order, tolerance, N), shared by all histories of that length. A short run pays
// for a short compression (at 1e-12: 1.3M to 2.5M instructions and Q = 52 to 57 at N = 2^13,
// against 5M to 10M and Q = 77 to 82 at 2^24), and its modes depend on its own length only.
//
// Stepping (src/fractional/soe_kernels.hpp): the modes' inputs are n0 steps old, so they are
// advanced a few steps at a time and their far sums kept; each step then adds the window.
#include <cstddef>
#include <memory>
#include <vector>

#include "adjoin/fractional/history.hpp"
#include "adjoin/fractional/weights.hpp"

namespace adjoin {

struct SoeCompression {
  WeightRule rule = WeightRule::bdf2;
  double order = 0.0;
  double tolerance = 0.0;
  std::size_t window = 0;     // n0: lags 1..n0-1 are summed directly
  std::vector<double> near;   // the exact w_0..w_{n0-1}
  // 0, 0, w_{n0-1}, ..., w_2: the window's sum runs forwards over y_{m-n0-1}..y_{m-2}, and
  // w_1 y_{m-1} is added last (src/fractional/soe_kernels.hpp)
  std::vector<double> near_shifted;
  // One-term modes (count `single`, padded with zeros to a multiple of 4):
  //     s <- s + (gain y_{m-n0} - decay s),
  // mode k's weight at lag n >= n0 being gain_k (1 - decay_k)^(n - n0).
  std::size_t single = 0;
  std::vector<double> decay, gain;
  // Two-term modes (count `paired`, padded likewise):
  //     s <- a s' + b s'' + p y_{m-n0} + r y_{m-n0-1}   (s', s'': the last two values),
  // mode k's weights W_n0 = p, W_n0+1 = r + a p, W_n = a W_n-1 + b W_n-2.
  std::size_t paired = 0;
  std::vector<double> a, b, p, r;
  std::size_t design_length = 0;  // N: verified for lags n0..N
  double error = 0.0;             // the largest relative weight error found, lags n0..N

  // Q: the number of recurrences per element (one- and two-term).
  std::size_t modes() const { return single + paired; }
  // The weight the compression applies at lag n (exact below the window).
  double weight(std::size_t n) const;
  std::size_t bytes() const;
};

// The compression for lags up to `last_lag` (its design length: bit_ceil(last_lag), at least
// 2^10), made on first use and cached per (rule, order, tolerance, design length) for the
// process (thread-safe). 0 < order < 1, 1e-15 <= tolerance < 1
// (std::invalid_argument otherwise; below about 1e-14 the reported error stays above the
// tolerance: the weights are doubles).
std::shared_ptr<const SoeCompression> soe_compression(WeightRule rule, double order, double tolerance,
                                                      std::size_t last_lag);

class SoeHistory final : public ConvolutionHistory {
 public:
  // Accepts `count` pushes (y_0..y_{count-1}), like a DirectHistory given `count` weights.
  SoeHistory(std::shared_ptr<const SoeCompression> compression, std::size_t count);

  double lag_sum() const override { return lag_sum_; }
  double push(double y) override;
  std::size_t size() const override { return pushed_; }
  std::size_t bytes() const override;
  double weight_error() const override { return c_->error; }
  std::size_t modes() const override { return c_->modes(); }

 private:
  std::shared_ptr<const SoeCompression> c_;
  std::size_t count_;
  std::size_t pushed_ = 0;
  // The last values y, in a line that is shifted back when full (so the near sum reads them
  // in order): y_{m-j} = recent_[end_ - j].
  std::vector<double> recent_;
  std::size_t end_ = 0;
  std::vector<double> s_;           // one-term states
  std::vector<double> s1_, s2_;     // two-term states: the last and the one before
  // The far sums (lags >= n0) of the steps made ahead (soe_kernels.hpp): far_[k] is that of
  // step m0 + k, m0 the step at which they were made.
  std::vector<double> far_;
  double lag_sum_ = 0.0;
};

}  // namespace adjoin

#include "adjoin/fractional/soe_history.hpp"

#include <algorithm>
#include <stdexcept>

#include "../detail/dot.hpp"
#include "../detail/simd_clones.hpp"

namespace adjoin {
namespace {

constexpr std::size_t kShift = 223;  // values kept past the window before the line is shifted back (n0 + 1 + this = 256)

// One step of the one-term modes (n a multiple of 4): s <- s + (g y - d s); returns sum s.
// Independent partial sums, as in detail/dot.cpp, so the loop runs in vector registers.
ADJOIN_SIMD_CLONES
double step_single(double* __restrict s, const double* __restrict decay, const double* __restrict gain, std::size_t n,
                   double y) {
  double sum[4] = {};
  for (std::size_t q = 0; q < n; q += 4)
    for (std::size_t k = 0; k < 4; ++k) {
      const double v = s[q + k] + (gain[q + k] * y - decay[q + k] * s[q + k]);
      s[q + k] = v;
      sum[k] += v;
    }
  return (sum[0] + sum[1]) + (sum[2] + sum[3]);
}

// One step of the two-term modes: s <- a s1 + b s2 + p y + r y_before, s2 <- s1, s1 <- s.
ADJOIN_SIMD_CLONES
double step_paired(double* __restrict s1, double* __restrict s2, const double* __restrict a, const double* __restrict b,
                   const double* __restrict p, const double* __restrict r, std::size_t n, double y, double y_before) {
  double sum[4] = {};
  for (std::size_t q = 0; q < n; q += 4)
    for (std::size_t k = 0; k < 4; ++k) {
      const double v = (a[q + k] * s1[q + k] + b[q + k] * s2[q + k]) + (p[q + k] * y + r[q + k] * y_before);
      s2[q + k] = s1[q + k];
      s1[q + k] = v;
      sum[k] += v;
    }
  return (sum[0] + sum[1]) + (sum[2] + sum[3]);
}

}  // namespace

SoeHistory::SoeHistory(std::shared_ptr<const SoeCompression> compression, std::size_t count)
    : c_(std::move(compression)),
      count_(count),
      recent_(c_->window + 1 + kShift, 0.0),
      end_(c_->window + 1),  // y_{-n0-1}..y_{-1} = 0: the modes read y_{m-n0-1} from the start
      s_(c_->decay.size(), 0.0),
      s1_(c_->a.size(), 0.0),
      s2_(c_->a.size(), 0.0) {}

void SoeHistory::push(double y) {
  if (pushed_ >= count_) throw std::logic_error("SoeHistory: more values pushed than weights were given");
  if (end_ == recent_.size()) {  // keep the last n0 + 1 values, at the front
    const std::size_t keep = c_->window + 1;
    std::copy(recent_.end() - static_cast<std::ptrdiff_t>(keep), recent_.end(), recent_.begin());
    end_ = keep;
  }
  recent_[end_++] = y;
  const std::size_t m = ++pushed_;  // the next step
  if (m >= count_) { lag_sum_ = 0.0; return; }
  // Lags n0.. from the modes (their inputs y_{m-n0}, y_{m-n0-1}), lags 1..n0-1 directly.
  const std::size_t n0 = c_->window;
  const double y_n0 = recent_[end_ - n0], y_after = recent_[end_ - n0 - 1];
  double far = step_single(s_.data(), c_->decay.data(), c_->gain.data(), s_.size(), y_n0);
  if (!s1_.empty())
    far += step_paired(s1_.data(), s2_.data(), c_->a.data(), c_->b.data(), c_->p.data(), c_->r.data(), s1_.size(), y_n0,
                       y_after);
  // sum_{j=1}^{n0-1} w_j y_{m-j} as a forward product of y_{m-n0}..y_{m-1} with 0, w_{n0-1}..w_1
  // (the zeros before y_0 stand in for the values not pushed yet).
  lag_sum_ = far + detail::dot(recent_.data() + end_ - n0, c_->near_reversed.data(), n0);
}

std::size_t SoeHistory::bytes() const {
  return sizeof(*this) + c_->bytes() + (recent_.capacity() + s_.capacity() + s1_.capacity() + s2_.capacity()) * sizeof(double);
}

}  // namespace adjoin

#include "adjoin/fractional/soe_history.hpp"

#include <algorithm>
#include <stdexcept>

#include "../detail/simd_clones.hpp"
#include "soe_kernels.hpp"

namespace adjoin {
namespace {

using soe_detail::kAhead;
using soe_detail::V4;
namespace sd = soe_detail;

constexpr std::size_t kShift = 223;  // values kept past the window before the line is shifted back (n0 + 1 + this = 256)

// The modes' far sums of kAhead steps (soe_kernels.hpp), four modes to a vector: lane j of the
// accumulators adds modes j, j + 4, ... in order. Each vector of modes takes all kAhead steps
// at once (its states stay in registers), two vectors side by side: one vector's steps form a
// chain of 2 kAhead dependent operations, and the processor overlaps too few such chains alone.
// `in` holds the inputs y_{m-n0-1}..y_{m-n0+kAhead-1} of the steps m..m+kAhead-1; far[k] = the
// far sum of step m + k. n and n2 are multiples of 4.
ADJOIN_SIMD_CLONES
void far_ahead(double* __restrict s, const double* __restrict decay, const double* __restrict gain, std::size_t n,
               double* __restrict s1, double* __restrict s2, const double* __restrict pa, const double* __restrict pb,
               const double* __restrict pp, const double* __restrict pr, std::size_t n2, const double* __restrict in,
               double* __restrict far) {
  V4 sum[kAhead] = {};
  std::size_t q = 0;
  for (; q + 8 <= n; q += 8) {
    const V4 d0 = sd::load(decay + q), g0 = sd::load(gain + q), d1 = sd::load(decay + q + 4), g1 = sd::load(gain + q + 4);
    V4 v0 = sd::load(s + q), v1 = sd::load(s + q + 4);
    for (std::size_t k = 0; k < kAhead; ++k) {
      const V4 y = sd::splat(in[k + 1]);
      v0 = sd::single_step(v0, d0, g0, y);
      v1 = sd::single_step(v1, d1, g1, y);
      sum[k] += v0;
      sum[k] += v1;
    }
    sd::store(s + q, v0);
    sd::store(s + q + 4, v1);
  }
  if (q < n) {
    const V4 d = sd::load(decay + q), g = sd::load(gain + q);
    V4 v = sd::load(s + q);
    for (std::size_t k = 0; k < kAhead; ++k) {
      v = sd::single_step(v, d, g, sd::splat(in[k + 1]));
      sum[k] += v;
    }
    sd::store(s + q, v);
  }
  for (std::size_t k = 0; k < kAhead; ++k) far[k] = (sum[k][0] + sum[k][1]) + (sum[k][2] + sum[k][3]);
  if (n2 == 0) return;
  V4 two[kAhead] = {};
  for (q = 0; q < n2; q += 4) {
    const V4 a = sd::load(pa + q), b = sd::load(pb + q), p = sd::load(pp + q), r = sd::load(pr + q);
    V4 last = sd::load(s1 + q), before = sd::load(s2 + q);
    for (std::size_t k = 0; k < kAhead; ++k) {
      const V4 v = sd::paired_step(last, before, a, b, p, r, sd::splat(in[k + 1]), sd::splat(in[k]));
      before = last;
      last = v;
      two[k] += v;
    }
    sd::store(s1 + q, last);
    sd::store(s2 + q, before);
  }
  for (std::size_t k = 0; k < kAhead; ++k) far[k] += (two[k][0] + two[k][1]) + (two[k][2] + two[k][3]);
}

// The lag sum (far + window) + w1 y[n] (soe_kernels.hpp): the window sum_{i<n} y[i] v[i] in
// four partial sums, n a multiple of 4. (All in the clone: its fused multiply-adds are the
// bank's.)
ADJOIN_SIMD_CLONES
double lag_of(const double* __restrict y, const double* __restrict v, std::size_t n, double w1, double far) {
  V4 sum = {};
  for (std::size_t i = 0; i < n; i += 4) sum += sd::load(y + i) * sd::load(v + i);
  const double window = (sum[0] + sum[1]) + (sum[2] + sum[3]);
  return (far + window) + w1 * y[n];
}

}  // namespace

SoeHistory::SoeHistory(std::shared_ptr<const SoeCompression> compression, std::size_t count)
    : c_(std::move(compression)),
      count_(count),
      recent_(c_->window + 1 + kShift, 0.0),
      end_(c_->window + 1),  // y_{-n0-1}..y_{-1} = 0: the modes read y_{m-n0-1} from the start
      s_(c_->decay.size(), 0.0),
      s1_(c_->a.size(), 0.0),
      s2_(c_->a.size(), 0.0),
      far_(kAhead, 0.0) {
  if (c_->window % 4 != 0 || c_->window < kAhead)
    throw std::logic_error("SoeHistory: the window must be a multiple of 4, at least the steps made ahead");
}

double SoeHistory::push(double y) {
  if (pushed_ >= count_) throw std::logic_error("SoeHistory: more values pushed than weights were given");
  if (end_ == recent_.size()) {  // keep the last n0 + 1 values, at the front
    const std::size_t keep = c_->window + 1;
    std::copy(recent_.end() - static_cast<std::ptrdiff_t>(keep), recent_.end(), recent_.begin());
    end_ = keep;
  }
  recent_[end_++] = y;
  const std::size_t m = ++pushed_;  // the next step
  if (m >= count_) return lag_sum_ = 0.0;
  const std::size_t n0 = c_->window;
  const double* first = recent_.data() + end_ - n0 - 1;  // y_{m-n0-1}
  const std::size_t k = (m - 1) % kAhead;
  if (k == 0)  // the far sums of steps m..m+kAhead-1, from y_{m-n0-1}..y_{m-n0+kAhead-1}
    far_ahead(s_.data(), c_->decay.data(), c_->gain.data(), s_.size(), s1_.data(), s2_.data(), c_->a.data(),
              c_->b.data(), c_->p.data(), c_->r.data(), s1_.size(), first, far_.data());
  return lag_sum_ = lag_of(first, c_->near_shifted.data(), n0, c_->near[1], far_[k]);
}

std::size_t SoeHistory::bytes() const {
  return sizeof(*this) + c_->bytes() +
         (recent_.capacity() + s_.capacity() + s1_.capacity() + s2_.capacity() + far_.capacity()) * sizeof(double);
}

}  // namespace adjoin

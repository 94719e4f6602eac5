#include "adjoin/fractional/soe_bank.hpp"

#include <algorithm>
#include <stdexcept>

#include "../detail/simd_clones.hpp"
#include "soe_kernels.hpp"

namespace adjoin {
namespace {

constexpr std::size_t L = SoeBank::kLanes;
constexpr std::size_t kShift = 223;  // rows kept past the window before the line is shifted back (as SoeHistory)
// Rows of padding after each block's line: 256 rows of 32 bytes are 8 kB, so without it the rows
// the blocks read and write in a step were 8 kB apart, all in one set of the 8-way L1 cache (a
// bank of 40 members has 10 blocks: every push and window missed L1; the pushes alone took 7 ns
// a member in the 2 x 20 Zener building). With 64 bytes more, each block's rows fall in a set of
// their own.
constexpr std::size_t kPad = 2;

using soe_detail::kAhead;
using soe_detail::V4;
namespace sd = soe_detail;


// The far sums of kAhead steps of one block of four members (soe_kernels.hpp): SoeHistory's
// arithmetic lane by lane. Its lanes are four modes, each accumulating modes j, j + 4, ...; here
// the lanes are members, so the modes are taken in four passes, pass j over modes j, j + 4, ...,
// with partial sums of its own. Two modes are stepped side by side (each mode's kAhead steps are
// a chain of 2 kAhead dependent operations; one chain at a time left the processor waiting).
// `y` holds the block's inputs y_{m-n0-1}..y_{m-n0+kAhead-1} of steps m..m+kAhead-1; far[k] = the
// far sums of step m + k. The states of mode q are at s[q * L] (and s1, s2), its coefficients at
// decay[q * L] (and the others) repeated over the lanes (a vector load each: GCC made the
// broadcasts of adjacent scalars into loads and lane permutes, which cost more). single and
// paired are multiples of 4.
struct Coefficients {
  const double *decay, *gain, *a, *b, *p, *r, *window;  // (wide: repeated over the lanes)
  std::size_t single, paired, n0;
  double w1;
};

// Pass j of the one-term modes: sum[k] = the modes j, j + 4, ... added in order at step m + k.
[[gnu::always_inline]] inline void single_pass(const Coefficients& c, double* __restrict s, const V4* y, std::size_t j,
                                               V4* sum) {
  for (std::size_t k = 0; k < kAhead; ++k) sum[k] = V4{};
  std::size_t q = j;
  for (; q + 4 < c.single; q += 8) {
    const std::size_t i0 = q * L, i1 = (q + 4) * L;
    const V4 d0 = sd::load(c.decay + i0), g0 = sd::load(c.gain + i0);
    const V4 d1 = sd::load(c.decay + i1), g1 = sd::load(c.gain + i1);
    V4 v0 = sd::load(s + i0), v1 = sd::load(s + i1);
    for (std::size_t k = 0; k < kAhead; ++k) {
      v0 = sd::single_step(v0, d0, g0, y[k + 1]);
      v1 = sd::single_step(v1, d1, g1, y[k + 1]);
      sum[k] += v0;
      sum[k] += v1;
    }
    sd::store(s + i0, v0);
    sd::store(s + i1, v1);
  }
  if (q < c.single) {
    const std::size_t i0 = q * L;
    const V4 d0 = sd::load(c.decay + i0), g0 = sd::load(c.gain + i0);
    V4 v0 = sd::load(s + i0);
    for (std::size_t k = 0; k < kAhead; ++k) {
      v0 = sd::single_step(v0, d0, g0, y[k + 1]);
      sum[k] += v0;
    }
    sd::store(s + i0, v0);
  }
}

// Pass j of the two-term modes, likewise.
[[gnu::always_inline]] inline void paired_pass(const Coefficients& c, double* __restrict s1, double* __restrict s2,
                                               const V4* y, std::size_t j, V4* sum) {
  for (std::size_t k = 0; k < kAhead; ++k) sum[k] = V4{};
  for (std::size_t q = j; q < c.paired; q += 4) {
    const std::size_t i = q * L;
    const V4 a = sd::load(c.a + i), b = sd::load(c.b + i), p = sd::load(c.p + i), r = sd::load(c.r + i);
    V4 last = sd::load(s1 + i), before = sd::load(s2 + i);
    for (std::size_t k = 0; k < kAhead; ++k) {
      const V4 v = sd::paired_step(last, before, a, b, p, r, y[k + 1], y[k]);
      before = last;
      last = v;
      sum[k] += v;
    }
    sd::store(s1 + i, last);
    sd::store(s2 + i, before);
  }
}

// total[k] = (P0 + P1) + (P2 + P3) of the four passes' sums.
template <class Pass>
[[gnu::always_inline]] inline void four_passes(Pass pass, V4* total) {
  V4 low[kAhead], high[kAhead], next[kAhead];
  pass(0, low);
  pass(1, next);
  for (std::size_t k = 0; k < kAhead; ++k) low[k] += next[k];
  pass(2, high);
  pass(3, next);
  for (std::size_t k = 0; k < kAhead; ++k) total[k] = low[k] + (high[k] + next[k]);
}

[[gnu::always_inline]] inline void far_ahead_block(const Coefficients& c, double* __restrict s, double* __restrict s1,
                                                   double* __restrict s2, const V4* y, double* __restrict far) {
  V4 total[kAhead];
  four_passes([&](std::size_t j, V4* sum) { single_pass(c, s, y, j, sum); }, total);
  if (c.paired > 0) {
    V4 two[kAhead];
    four_passes([&](std::size_t j, V4* sum) { paired_pass(c, s1, s2, y, j, sum); }, two);
    for (std::size_t k = 0; k < kAhead; ++k) total[k] += two[k];
  }
  for (std::size_t k = 0; k < kAhead; ++k) sd::store(far + k * L, total[k]);
}

// The lag sums (far + window) + w_1 y_{m-1} of G blocks, the window in SoeHistory's four
// partial sums; each weight, loaded once, serves the G blocks. `rows` is the first block's row
// y_{m-n0-1} (the next block's is `stride` further), `far` its far sum of this step.
template <std::size_t G>
[[gnu::always_inline]] inline void lag_blocks(const Coefficients& c, const double* __restrict rows, std::size_t stride,
                                              const double* __restrict far, double* __restrict lag) {
  V4 sum[G][4] = {};
  for (std::size_t i = 0; i < c.n0; i += 4)
    for (std::size_t u = 0; u < 4; ++u) {
      const V4 w = sd::load(c.window + (i + u) * L);
      for (std::size_t g = 0; g < G; ++g) sum[g][u] += sd::load(rows + g * stride + (i + u) * L) * w;
    }
  for (std::size_t g = 0; g < G; ++g) {
    const V4 window = (sum[g][0] + sum[g][1]) + (sum[g][2] + sum[g][3]);
    sd::store(lag + g * L,
              (sd::load(far + g * kAhead * L) + window) + sd::splat(c.w1) * sd::load(rows + g * stride + c.n0 * L));
  }
}

// One step of every block: the far sums made ahead when k = 0, then the lag sums. `rows` is
// the first block's row y_{m-n0-1} (the next block's is `stride` further).
ADJOIN_SIMD_CLONES
void step_blocks(const Coefficients& c, std::size_t blocks, std::size_t k, double* __restrict s, double* __restrict s1,
                 double* __restrict s2, const double* __restrict rows, std::size_t stride, double* __restrict far,
                 double* __restrict lag) {
  if (k == 0)
    for (std::size_t blk = 0; blk < blocks; ++blk) {
      V4 y[kAhead + 1];
      for (std::size_t i = 0; i <= kAhead; ++i) y[i] = sd::load(rows + blk * stride + i * L);
      far_ahead_block(c, s + blk * c.single * L, s1 + blk * c.paired * L, s2 + blk * c.paired * L, y,
                      far + blk * kAhead * L);
    }
  std::size_t blk = 0;
  for (; blk + 3 <= blocks; blk += 3)
    lag_blocks<3>(c, rows + blk * stride, stride, far + (blk * kAhead + k) * L, lag + blk * L);
  for (; blk < blocks; ++blk) lag_blocks<1>(c, rows + blk * stride, stride, far + (blk * kAhead + k) * L, lag + blk * L);
}

}  // namespace

SoeBank::SoeBank(std::shared_ptr<const SoeCompression> compression, std::size_t count, std::size_t members)
    : c_(std::move(compression)),
      count_(count),
      members_(members),
      blocks_((members + L - 1) / L),
      staged_at_(members, 0),
      line_(c_->window + 1 + kShift),
      pitch_((line_ + kPad) * L),
      end_(c_->window + 1),  // y_{-n0-1}..y_{-1} = 0: the modes read y_{m-n0-1} from the start
      recent_(blocks_ * pitch_, 0.0),
      s_(blocks_ * c_->decay.size() * L, 0.0),
      s1_(blocks_ * c_->a.size() * L, 0.0),
      s2_(blocks_ * c_->a.size() * L, 0.0),
      far_(blocks_ * kAhead * L, 0.0),
      lag_(blocks_ * L, 0.0) {
  if (members == 0) throw std::invalid_argument("SoeBank: no members");
  if (c_->window % 4 != 0 || c_->window < kAhead)
    throw std::logic_error("SoeBank: the window must be a multiple of 4, at least the steps made ahead");
  auto spread = [](const std::vector<double>& v) {
    std::vector<double> out(v.size() * L);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = v[i / L];
    return out;
  };
  wide_ = Wide{spread(c_->decay), spread(c_->gain), spread(c_->a), spread(c_->b),
               spread(c_->p),     spread(c_->r),    spread(c_->near_shifted)};
}

void SoeBank::refuse() const {
  if (pushed_ >= count_) throw std::logic_error("SoeBank: more values pushed than weights were given");
  throw std::logic_error("SoeBank: a member pushed twice before the others pushed once");
}

void SoeBank::step() {
  ++end_;
  staged_count_ = 0;
  const std::size_t m = ++pushed_;  // the next step
  if (m >= count_) {
    std::fill(lag_.begin(), lag_.end(), 0.0);
    return;
  }
  const std::size_t n0 = c_->window;
  const Coefficients c{wide_.decay.data(), wide_.gain.data(), wide_.a.data(), wide_.b.data(), wide_.p.data(),
                       wide_.r.data(),     wide_.window.data(), c_->decay.size(), c_->a.size(), n0, c_->near[1]};
  step_blocks(c, blocks_, (m - 1) % kAhead, s_.data(), s1_.data(), s2_.data(), recent_.data() + (end_ - n0 - 1) * L,
              pitch_, far_.data(), lag_.data());
  if (end_ == line_) {  // keep the last n0 + 1 rows of each block, at the front, for the next pushes
    const std::size_t keep = n0 + 1;
    for (std::size_t blk = 0; blk < blocks_; ++blk) {
      double* line = recent_.data() + blk * pitch_;
      std::copy(line + (line_ - keep) * L, line + line_ * L, line);
    }
    end_ = keep;
  }
}

std::size_t SoeBank::bytes() const {
  return sizeof(*this) + c_->bytes() +
         (recent_.capacity() + s_.capacity() + s1_.capacity() + s2_.capacity() + far_.capacity() + lag_.capacity() +
          wide_.decay.capacity() + wide_.gain.capacity() + wide_.a.capacity() + wide_.b.capacity() + wide_.p.capacity() +
          wide_.r.capacity() + wide_.window.capacity()) *
             sizeof(double) +
         staged_at_.capacity() * sizeof(std::size_t);
}

}  // namespace adjoin

#pragma once
// The peaks of many signals sampled at the same grid points, in arrays (a building run's
// channels: study/channel_observer.hpp). Signals 0..smooth-1 follow SmoothPeak's rule
// (peaks.hpp: refined between samples by the cubic through the last four), the others Peak's
// (the largest sample).
//
//     PeakTable table;
//     table.reset(smooth, n);              // n signals, the first `smooth` of them refined
//     read_values(table.row());            // each grid point: write the new samples ...
//     table.update(t);                     // ... then update the peaks
//
// The last four rows of samples are kept in a ring, so nothing is copied per step. A step
// first asks, in one pass over the arrays that the compiler vectorises, whether any signal has
// a new peak or (smooth) a sample before last that is a local maximum of |y| as large as its
// peak; only then does it go through the signals one by one (early in a record, a few steps
// in ten; later, rarely). The peaks are SmoothPeak's and Peak's, bit for bit.
#include <cmath>
#include <cstddef>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define ADJOIN_PEAK_TABLE_AVX 1
#endif

#include "adjoin/observe/extremum.hpp"
#include "adjoin/observe/peaks.hpp"

namespace adjoin {

class PeakTable {
 public:
  // (allow_avx = false: the SSE2 path even where the CPU has AVX, for the tests.)
  void reset(std::size_t smooth, std::size_t n, bool allow_avx = true) {
    n_ = n;
    smooth_ = smooth;
    rows_.assign(4 * n_, 0.0);
    max_.assign(n_, 0.0);
    t_.assign(n_, 0.0);
    newest_ = 0;
    count_ = 0;
    t1_ = 0.0;
#ifdef ADJOIN_PEAK_TABLE_AVX
    avx_ = allow_avx && __builtin_cpu_supports("avx");
#else
    (void)allow_avx;
#endif
  }
  std::size_t size() const { return n_; }
  // Where the samples of the next grid point go (size() of them).
  double* row() { return rows_.data() + n_ * ((newest_ + 1) & 3); }
  // The samples of the last grid point updated.
  const double* last() const { return rows_.data() + n_ * newest_; }
  Peak peak(std::size_t k) const { return {max_[k], t_[k]}; }

  // The samples in row() are at time t: update every peak.
  void update(double t) {
    const std::size_t now = (newest_ + 1) & 3;
    if (changes(now)) update_each(now, t);
    newest_ = now;
    t1_ = t;
    ++count_;
  }

 private:
  static constexpr double kTie = 1.0 + 1e-12;  // Peak::update: a new peak beats the old by more than rounding

  const double* at(std::size_t row) const { return rows_.data() + n_ * (row & 3); }

  // Whether any peak changes at this step (a superset: refinement also needs count_ >= 2).
  // Two signals at a time in SSE2 registers (every x86-64 has them; the compiler does not
  // vectorise this mix of compares itself), one at a time elsewhere.
  bool changes(std::size_t now) const {
    const double *y = at(now), *y1 = at(newest_), *y0 = at(newest_ + 3), *max = max_.data();
#ifdef ADJOIN_PEAK_TABLE_AVX
    if (avx_) return changes_avx(y, y1, y0, max, smooth_, n_);
#endif
    std::size_t k = 0;
#if defined(__SSE2__)
    const __m128d sign = _mm_set1_pd(-0.0), tie = _mm_set1_pd(kTie);
    __m128d any = _mm_setzero_pd();
    for (; k + 2 <= smooth_; k += 2) {
      const __m128d a = _mm_andnot_pd(sign, _mm_loadu_pd(y + k)), a1 = _mm_andnot_pd(sign, _mm_loadu_pd(y1 + k));
      const __m128d a0 = _mm_andnot_pd(sign, _mm_loadu_pd(y0 + k)), m = _mm_loadu_pd(max + k);
      const __m128d local = _mm_and_pd(_mm_and_pd(_mm_cmpge_pd(a1, a0), _mm_cmpgt_pd(a1, a)), _mm_cmpge_pd(a1, m));
      any = _mm_or_pd(any, _mm_or_pd(local, _mm_cmpgt_pd(a, _mm_mul_pd(m, tie))));
    }
    if (_mm_movemask_pd(any) != 0) return true;
#endif
    for (; k < smooth_; ++k) {
      const double a = std::fabs(y[k]), a1 = std::fabs(y1[k]);
      if (a > max[k] * kTie || (a1 >= std::fabs(y0[k]) && a1 > a && a1 >= max[k])) return true;
    }
#if defined(__SSE2__)
    for (; k + 2 <= n_; k += 2) {
      const __m128d a = _mm_andnot_pd(sign, _mm_loadu_pd(y + k));
      any = _mm_or_pd(any, _mm_cmpgt_pd(a, _mm_mul_pd(_mm_loadu_pd(max + k), tie)));
    }
    if (_mm_movemask_pd(any) != 0) return true;
#endif
    for (; k < n_; ++k)
      if (std::fabs(y[k]) > max[k] * kTie) return true;
    return false;
  }

#ifdef ADJOIN_PEAK_TABLE_AVX
  // changes() four signals at a time where the CPU has AVX (chosen in reset()): the same
  // tests, so the same answer. The last 1 to 3 signals of each kind go in masked lanes (read
  // as 0 with a peak of 0, which no test passes), not one by one.
  __attribute__((target("avx"))) static bool changes_avx(const double* y, const double* y1, const double* y0,
                                                         const double* max, std::size_t smooth, std::size_t n) {
    alignas(32) static constexpr long long kLanes[8] = {-1, -1, -1, -1, 0, 0, 0, 0};  // `left` lanes on at 4 - left
    const __m256d sign = _mm256_set1_pd(-0.0), tie = _mm256_set1_pd(kTie);
    __m256d any = _mm256_setzero_pd();
    std::size_t k = 0;
    for (; k + 4 <= smooth; k += 4) {
      const __m256d a = _mm256_andnot_pd(sign, _mm256_loadu_pd(y + k)), a1 = _mm256_andnot_pd(sign, _mm256_loadu_pd(y1 + k));
      const __m256d a0 = _mm256_andnot_pd(sign, _mm256_loadu_pd(y0 + k)), m = _mm256_loadu_pd(max + k);
      const __m256d local = _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(a1, a0, _CMP_GE_OQ), _mm256_cmp_pd(a1, a, _CMP_GT_OQ)),
                                          _mm256_cmp_pd(a1, m, _CMP_GE_OQ));
      any = _mm256_or_pd(any, _mm256_or_pd(local, _mm256_cmp_pd(a, _mm256_mul_pd(m, tie), _CMP_GT_OQ)));
    }
    if (k < smooth) {  // (the same, masked)
      const __m256i mask = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kLanes + 4 - (smooth - k)));
      const __m256d a = _mm256_andnot_pd(sign, _mm256_maskload_pd(y + k, mask));
      const __m256d a1 = _mm256_andnot_pd(sign, _mm256_maskload_pd(y1 + k, mask));
      const __m256d a0 = _mm256_andnot_pd(sign, _mm256_maskload_pd(y0 + k, mask)), m = _mm256_maskload_pd(max + k, mask);
      const __m256d local = _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(a1, a0, _CMP_GE_OQ), _mm256_cmp_pd(a1, a, _CMP_GT_OQ)),
                                          _mm256_cmp_pd(a1, m, _CMP_GE_OQ));
      any = _mm256_or_pd(any, _mm256_or_pd(local, _mm256_cmp_pd(a, _mm256_mul_pd(m, tie), _CMP_GT_OQ)));
    }
    for (k = smooth; k + 4 <= n; k += 4) {
      const __m256d a = _mm256_andnot_pd(sign, _mm256_loadu_pd(y + k));
      any = _mm256_or_pd(any, _mm256_cmp_pd(a, _mm256_mul_pd(_mm256_loadu_pd(max + k), tie), _CMP_GT_OQ));
    }
    if (k < n) {  // (the same, masked)
      const __m256i mask = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kLanes + 4 - (n - k)));
      const __m256d a = _mm256_andnot_pd(sign, _mm256_maskload_pd(y + k, mask));
      any = _mm256_or_pd(any, _mm256_cmp_pd(a, _mm256_mul_pd(_mm256_maskload_pd(max + k, mask), tie), _CMP_GT_OQ));
    }
    return _mm256_movemask_pd(any) != 0;
  }
#endif

  // SmoothPeak::update and Peak::update, signal by signal.
  void update_each(std::size_t now, double t) {
    const double *y = at(now), *y1 = at(newest_), *y0 = at(newest_ + 3), *ym = at(newest_ + 2);
    for (std::size_t k = 0; k < smooth_; ++k) {
      const double a = std::fabs(y[k]), a1 = std::fabs(y1[k]);
      if (count_ >= 2 && a1 >= std::fabs(y0[k]) && a1 > a && a1 >= max_[k]) {
        // |y| has a local maximum at the sample before: the cubic through it, the two before
        // and the new one (time O(h^3)), or with only three samples the parabola.
        const double h = t - t1_;
        const Vertex v = count_ >= 3 ? cubic_extremum(t1_ - 2.0 * h, h, ym[k], y0[k], y1[k], y[k])
                                     : parabola_vertex(t1_, h, y0[k], y1[k], y[k]);
        const double refined = std::fabs(v.y);
        if (refined >= a1) { max_[k] = refined; t_[k] = v.t; }
      }
      raise(k, a, t);
    }
    for (std::size_t k = smooth_; k < n_; ++k) raise(k, std::fabs(y[k]), t);
  }
  void raise(std::size_t k, double a, double t) {
    if (a > max_[k] * kTie) { max_[k] = a; t_[k] = t; }
  }

  std::size_t n_ = 0, smooth_ = 0;
  std::vector<double> rows_;  // 4 rows of n_ samples, a ring: row newest_ the last
  std::vector<double> max_, t_;  // each signal's peak |y| and its time
  std::size_t newest_ = 0;
  long count_ = 0;    // grid points updated
  double t1_ = 0.0;   // the last one's time
  bool avx_ = false;  // changes() takes the AVX path
};

}  // namespace adjoin

#include "adjoin/fractional/fft_history.hpp"

#include <fftw3.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <mutex>
#include <new>
#include <stdexcept>
#include <utility>

#include "../detail/dot.hpp"
#include "../detail/simd_clones.hpp"

namespace adjoin {
namespace {

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
template <class T>
using FftwArray = std::unique_ptr<T[], FftwFree>;

template <class T>
FftwArray<T> fftw_array(std::size_t n) {
  void* p = fftw_malloc(sizeof(T) * std::max<std::size_t>(n, 1));
  if (p == nullptr) throw std::bad_alloc();
  return FftwArray<T>(static_cast<T*>(p));
}

// A real-to-complex and complex-to-real pair of length n, planned in place (n + 2 doubles; in
// place is markedly faster than out of place once the arrays leave the cache) on fftw_malloc
// arrays. Plans are kept for the life of the process and shared: FFTW's planner is not
// thread-safe but executing a plan on new arrays (of the same alignment, which fftw_malloc
// guarantees) is.
struct PlanPair {
  fftw_plan forward = nullptr;
  fftw_plan backward = nullptr;
};

// FFTW_ESTIMATE with FFTW_NO_BUFFERING (one of fftw3.h's planner flags): the estimate's
// search over buffered variants made planning cost about 15M instructions per transform at
// length 256 and 27M at 2048, three quarters of a single 8,000-step run; without them 7M to
// 12M.
constexpr unsigned kPlannerFlags = FFTW_ESTIMATE | FFTW_NO_BUFFERING;

class PlanCache {
 public:
  PlanCache() = default;
  PlanCache(const PlanCache&) = delete;
  PlanCache& operator=(const PlanCache&) = delete;
  ~PlanCache() {
    for (auto& [n, plans] : plans_) {
      fftw_destroy_plan(plans.forward);
      fftw_destroy_plan(plans.backward);
    }
  }

  PlanPair get(std::size_t n) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = plans_.find(n);
    if (it != plans_.end()) return it->second;
    // FFTW_ESTIMATE plans without touching the array, so a scratch array suffices.
    auto spectrum = fftw_array<fftw_complex>(n / 2 + 1);
    double* real = spectrum.get()[0];
    const int len = static_cast<int>(n);
    PlanPair plans;
    plans.forward = fftw_plan_dft_r2c_1d(len, real, spectrum.get(), kPlannerFlags);
    plans.backward = fftw_plan_dft_c2r_1d(len, spectrum.get(), real, kPlannerFlags);
    if (plans.forward == nullptr || plans.backward == nullptr)
      throw std::runtime_error("FftHistory: FFTW could not plan a transform");
    plans_.emplace(n, plans);
    return plans;
  }

 private:
  std::mutex mutex_;
  std::map<std::size_t, PlanPair> plans_;
};

PlanCache& plan_cache() {
  static PlanCache cache;
  return cache;
}

// The hot loops below are also compiled for AVX2 with FMA, chosen at load time when the CPU
// has them (as FFTW chooses its own SIMD kernels): results then differ from the baseline
// build's only by rounding. The dot products live in detail/dot.hpp.

// s = x w, elementwise on interleaved complex values (s may be x).
ADJOIN_SIMD_CLONES
void multiply(double* s, const double* x, const double* __restrict w, std::size_t count) {
  for (std::size_t f = 0; f < 2 * count; f += 2) {
    const double xr = x[f], xi = x[f + 1];
    s[f] = xr * w[f] - xi * w[f + 1];
    s[f + 1] = xr * w[f + 1] + xi * w[f];
  }
}
// s += x w.
ADJOIN_SIMD_CLONES
void multiply_add(double* __restrict s, const double* __restrict x, const double* __restrict w,
                  std::size_t count) {
  for (std::size_t f = 0; f < 2 * count; f += 2) {
    s[f] += x[f] * w[f] - x[f + 1] * w[f + 1];
    s[f + 1] += x[f] * w[f + 1] + x[f + 1] * w[f];
  }
}

// Products of one tile (L values of y times L weights) that land on its first `outputs` steps.
std::size_t direct_products(std::size_t block, std::size_t outputs) {
  // Output t has min(t, L-1) - max(0, t-L+1) + 1 products: t + 1 below L, 2L - 1 - t above.
  if (outputs <= block) return outputs * (outputs + 1) / 2;
  const std::size_t e = outputs - block;
  return block * (block + 1) / 2 + e * block - e * (e + 1) / 2;
}

// The smallest FFT length that holds the first `outputs` terms of a convolution of two
// sequences of `outputs` terms without wrap-around into them: 2 outputs - 1, rounded up.
std::size_t truncated_length(std::size_t outputs) {
  return std::bit_ceil(std::max<std::size_t>(2 * outputs - 1, 2));
}

// How a window is formed (see choose() and Spectra::plan below).
enum class Method { direct, truncated, full };

// Costs in multiply-adds of a vectorised dot product: a real FFT of length n about
// 2 n log2 n of them (measured), a complex multiply-add about 2. The constants only move work
// between exact methods.
double fft_cost(std::size_t n) {
  const double x = static_cast<double>(n);
  return 2.0 * x * std::log2(x);
}

// The cheapest method for a window of `tiles` tiles of block length L with `outputs` wanted
// results, `new_weights` of whose weight spectra would be made for it:
//  - direct: one multiply-add per product;
//  - full: forward FFT of the new y block, inverse FFT of the window, spectrum products;
//  - truncated: only the first `outputs` values of each y block and weight partition matter,
//    so a fresh, shorter convolution of each tile (two forward FFTs) and one inverse FFT.
Method choose(std::size_t block, std::size_t tiles, std::size_t outputs, std::size_t new_weights) {
  const auto t = static_cast<double>(tiles);
  double best = static_cast<double>(2 + new_weights) * fft_cost(2 * block) +
                2.0 * t * static_cast<double>(block + 1) + static_cast<double>(2 * block);
  Method method = Method::full;
  const std::size_t n = truncated_length(outputs);
  if (n < 2 * block) {
    const double truncated = (2.0 * t + 1.0) * fft_cost(n) + 2.0 * t * static_cast<double>(n / 2 + 1) +
                             t * static_cast<double>(2 * n);
    if (truncated < best) {
      best = truncated;
      method = Method::truncated;
    }
  }
  if (t * static_cast<double>(direct_products(block, outputs)) <= best) method = Method::direct;
  return method;
}

}  // namespace

struct FftHistory::Spectra {
  struct Level {
    std::size_t block = 0;  // L: y block length and weight partition length
    std::size_t parts = 0;  // P: partitions p = 1..P, lags [pL, (p+1)L), with pL <= N
    std::size_t windows = 0;  // windows k = 0..windows-1 (steps (k+1) L <= N)
    PlanPair plans;         // length 2L, planned on first use
    // weights[p-1]: spectrum of w_{pL}..w_{pL+L-1} (zero past N), zero-padded to 2L and scaled
    // by 1/(2L); made on first use.
    std::vector<FftwArray<fftw_complex>> weights;
    // ring[k mod P]: spectrum of the y block k (zero-padded to 2L), made on first use;
    // ring_block says which block a slot holds (npos: none).
    std::vector<FftwArray<fftw_complex>> ring;
    std::vector<std::size_t> ring_block;
  };
  std::vector<Level> levels;
  FftwArray<fftw_complex> work;  // the product spectrum, work_size + 1 complex values
  std::size_t work_size = 0;

  // Tiles and wanted outputs of window k, given N + 1 = count.
  static std::size_t tiles(const Level& level, std::size_t k) { return std::min(level.parts, k + 1); }
  static std::size_t outputs(const Level& level, std::size_t k, std::size_t count) {
    return std::min(2 * level.block - 1, count - (k + 1) * level.block);
  }
  // How window k is formed. Only the last two windows of a level can want fewer than 2L - 1
  // outputs; the others are all full, so window k is the first user of W_{k+1} if k < P.
  static Method plan(const Level& level, std::size_t k, std::size_t count) {
    const std::size_t t = tiles(level, k);
    return choose(level.block, t, outputs(level, k, count), k < level.parts ? 1 : 0);
  }
};

FftHistory::FftHistory(std::vector<double> weights)
    : w_(std::move(weights)), spectra_(std::make_unique<Spectra>()) {
  static_assert(std::has_single_bit(kNear) && std::has_single_bit(kRatio) && kRatio >= 2,
                "block lengths must stay powers of two");
  if (w_.empty()) return;
  const std::size_t n_max = w_.size() - 1;  // N
  y_.reserve(w_.size());
  future_.assign(w_.size(), 0.0);

  // near_[i] = w_{n-i} for the lags n - i = 1..n, n = min(B, N); but lag B belongs to the
  // first level, so near_[0] = 0 if n = B (a zero that makes the near sum a whole number of
  // vector strides).
  const std::size_t near_count = std::min(kNear, n_max);
  near_.resize(near_count);
  for (std::size_t i = 0; i < near_count; ++i) near_[i] = w_[near_count - i];
  if (near_count == kNear) near_[0] = 0.0;

  // Levels L = B r^l <= N, each with the partitions its lags [L, rL) need up to N.
  for (std::size_t block = kNear; block <= n_max; block *= kRatio) {
    Spectra::Level level;
    level.block = block;
    level.windows = n_max / block;
    level.parts = std::min(kRatio - 1, level.windows);
    level.weights.resize(level.parts);
    level.ring.resize(level.parts);
    level.ring_block.assign(level.parts, static_cast<std::size_t>(-1));
    spectra_->levels.push_back(std::move(level));
    if (block > n_max / kRatio) break;  // the next block would pass N (or overflow)
  }
}

FftHistory::~FftHistory() = default;

void FftHistory::add_window(std::size_t index, std::size_t m) {
  // Step m = (k+1) L completes y block k. The window collects every tile (y block k', weight
  // partition p) with k' + p = k + 1: its products w_j y_i (i in block k', j in [pL, pL+L))
  // land on steps n = m .. m + 2L - 2 and none earlier; only n <= N are ever read.
  Spectra::Level& level = spectra_->levels[index];
  const std::size_t block = level.block;
  const std::size_t k = m / block - 1;
  const std::size_t tiles = Spectra::tiles(level, k);
  const std::size_t outputs = Spectra::outputs(level, k, w_.size());
  double* out = future_.data() + m;
  const Method method = Spectra::plan(level, k, w_.size());

  if (method == Method::direct) {
    // Output t (step m + t) of tile p: sum over q of y_{k'L+q} w_{pL+t-q}, 0 <= q < L,
    // 0 <= t - q < L.
    for (std::size_t p = 1; p <= tiles; ++p) {
      const double* y = y_.data() + (k + 1 - p) * block;
      const double* w = w_.data() + p * block;
      for (std::size_t t = 0; t < outputs; ++t) {
        const std::size_t q_lo = t >= block ? t - block + 1 : 0;
        const std::size_t q_hi = std::min(t, block - 1);
        out[t] += detail::dot_reversed(y + q_lo, w + (t - q_lo), q_hi - q_lo + 1);
      }
    }
    return;
  }

  if (method == Method::truncated) {
    // Outputs t < T only involve q <= t and t - q <= t: the first T values of each y block
    // and of each weight partition, convolved at the length n >= 2T - 1 (no wrap-around into
    // the first T terms). Fresh spectra: these windows come at most twice per level.
    const std::size_t n = truncated_length(outputs);
    const std::size_t half = n / 2 + 1;
    const PlanPair plans = plan_cache().get(n);
    auto sum = fftw_array<fftw_complex>(half);
    auto ys = fftw_array<fftw_complex>(half);
    auto ws = fftw_array<fftw_complex>(half);
    double* yr = ys.get()[0];
    double* wr = ws.get()[0];
    for (std::size_t p = 1; p <= tiles; ++p) {
      const double* y = y_.data() + (k + 1 - p) * block;
      const double* w = w_.data() + p * block;
      std::copy(y, y + outputs, yr);
      std::fill(yr + outputs, yr + n, 0.0);
      std::copy(w, w + outputs, wr);
      std::fill(wr + outputs, wr + n, 0.0);
      fftw_execute_dft_r2c(plans.forward, yr, ys.get());
      fftw_execute_dft_r2c(plans.forward, wr, ws.get());
      if (p == 1)
        multiply(sum.get()[0], ys.get()[0], ws.get()[0], half);
      else
        multiply_add(sum.get()[0], ys.get()[0], ws.get()[0], half);
    }
    double* real = sum.get()[0];
    fftw_execute_dft_c2r(plans.backward, sum.get(), real);
    const double scale = 1.0 / static_cast<double>(n);
    for (std::size_t t = 0; t < outputs; ++t) out[t] += scale * real[t];
    return;
  }

  const std::size_t half = block + 1;  // complex values of a length-2L real spectrum
  // The level's transforms, planned on its first full window: a level whose windows are all
  // formed directly or truncated (the last level of many runs) plans nothing.
  if (level.plans.forward == nullptr) level.plans = plan_cache().get(2 * block);
  // Weight spectra, on first use (in place: reals in, spectrum out).
  for (std::size_t p = 1; p <= tiles; ++p) {
    auto& spectrum = level.weights[p - 1];
    if (spectrum) continue;
    spectrum = fftw_array<fftw_complex>(half);
    double* real = spectrum.get()[0];
    const std::size_t begin = p * block, end = std::min(begin + block, w_.size());
    std::copy(w_.data() + begin, w_.data() + end, real);
    std::fill(real + (end - begin), real + 2 * block, 0.0);
    fftw_execute_dft_r2c(level.plans.forward, real, spectrum.get());
    // FFTW's transforms are unnormalised: fold 1/(2L) into the weights once.
    const double scale = 1.0 / (2.0 * static_cast<double>(block));
    for (std::size_t f = 0; f < half; ++f) {
      spectrum[f][0] *= scale;
      spectrum[f][1] *= scale;
    }
  }
  // Spectra of the y blocks k + 1 - tiles .. k (all but block k normally kept from before).
  for (std::size_t kb = k + 1 - tiles; kb <= k; ++kb) {
    const std::size_t slot = kb % level.parts;
    if (level.ring_block[slot] == kb) continue;
    auto& spectrum = level.ring[slot];
    if (!spectrum) spectrum = fftw_array<fftw_complex>(half);
    double* real = spectrum.get()[0];
    const double* y = y_.data() + kb * block;
    std::copy(y, y + block, real);
    std::fill(real + block, real + 2 * block, 0.0);
    fftw_execute_dft_r2c(level.plans.forward, real, spectrum.get());
    level.ring_block[slot] = kb;
  }

  // Whether a later full window reads block k's spectrum; if none does, the window's
  // spectrum overwrites it instead of taking the shared work array.
  bool kept = false;
  for (std::size_t k2 = k + 1; !kept && k2 < std::min(k + level.parts, level.windows); ++k2)
    kept = Spectra::plan(level, k2, w_.size()) == Method::full;
  fftw_complex* product;
  if (kept) {
    if (spectra_->work_size < block) {
      spectra_->work = fftw_array<fftw_complex>(half);
      spectra_->work_size = block;
    }
    product = spectra_->work.get();
  } else {
    product = level.ring[k % level.parts].get();
    level.ring_block[k % level.parts] = static_cast<std::size_t>(-1);
  }
  // The window's spectrum, sum over p of X_{k+1-p} W_p, in chunks that stay in the L1 cache.
  constexpr std::size_t kChunk = 256;
  for (std::size_t f0 = 0; f0 < half; f0 += kChunk) {
    const std::size_t count = std::min(kChunk, half - f0);
    multiply(product[f0], level.ring[k % level.parts][f0], level.weights[0][f0], count);
    for (std::size_t p = 2; p <= tiles; ++p)
      multiply_add(product[f0], level.ring[(k + 1 - p) % level.parts][f0], level.weights[p - 1][f0],
                   count);
  }
  double* real = product[0];
  fftw_execute_dft_c2r(level.plans.backward, product, real);
  for (std::size_t t = 0; t < outputs; ++t) out[t] += real[t];
}

double FftHistory::push(double y) {
  if (y_.size() >= w_.size())
    throw std::logic_error("FftHistory: more values pushed than weights were given");
  y_.push_back(y);
  const std::size_t m = y_.size();
  if (m >= w_.size()) return lag_sum_ = 0.0;  // past step N: never read

  // Every window that closes here: L divides m, for L = B, rB, r^2 B, ... (a power-of-two
  // ladder, so the first L that does not divide m ends the search). L is a power of two, so
  // the test is a mask rather than m % L, a 64-bit division every step (no gain measured
  // beyond the noise, but none lost).
  const auto& levels = spectra_->levels;
  for (std::size_t i = 0; i < levels.size() && (m & (levels[i].block - 1)) == 0; ++i) add_window(i, m);

  // Near lags j = 1..min(n, m): near_[i] = w_{n-i} with n = near_.size(), against
  // y_{m-n+i}.
  const std::size_t n = near_.size();
  const std::size_t i0 = m >= n ? 0 : n - m;
  return lag_sum_ = future_[m] + detail::dot(near_.data() + i0, y_.data() + (m + i0 - n), n - i0);
}

std::size_t FftHistory::bytes() const {
  std::size_t total = sizeof(*this) + sizeof(Spectra) +
                      (w_.capacity() + near_.capacity() + y_.capacity() + future_.capacity()) *
                          sizeof(double);
  total += spectra_->levels.capacity() * sizeof(Spectra::Level);
  for (const auto& level : spectra_->levels) {
    total += (level.weights.capacity() + level.ring.capacity()) * sizeof(FftwArray<fftw_complex>) +
             level.ring_block.capacity() * sizeof(std::size_t);
    for (const auto& s : level.weights)
      if (s) total += (level.block + 1) * sizeof(fftw_complex);
    for (const auto& s : level.ring)
      if (s) total += (level.block + 1) * sizeof(fftw_complex);
  }
  if (spectra_->work_size > 0) total += (spectra_->work_size + 1) * sizeof(fftw_complex);
  return total;
}

}  // namespace adjoin

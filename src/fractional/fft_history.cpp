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
    plans.forward = fftw_plan_dft_r2c_1d(len, real, spectrum.get(), FFTW_ESTIMATE);
    plans.backward = fftw_plan_dft_c2r_1d(len, spectrum.get(), real, FFTW_ESTIMATE);
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

// Whether a tile of block length L with `outputs` wanted results is cheaper by FFT. Direct:
// one multiply-add per product, vectorised; FFT: a forward and an inverse real transform of
// length 2L (about 2.5 n log2 n flops each, less efficient per flop) plus the pointwise
// product. The constant only moves work between two exact methods.
std::size_t direct_products(std::size_t block, std::size_t outputs) {
  if (outputs <= block) return outputs * (outputs + 1) / 2;
  return block * (block + 1) / 2 + (outputs - block) * block;
}
bool tile_by_fft(std::size_t block, std::size_t outputs) {
  const double n = 2.0 * static_cast<double>(block);
  const double fft_cost = 8.0 * n * std::log2(n) + 64.0;
  return static_cast<double>(direct_products(block, outputs)) > fft_cost;
}

}  // namespace

struct FftHistory::Spectra {
  struct Level {
    std::size_t block = 0;   // L: y block length and weight segment length
    bool fft = false;        // whether any of its tiles is done by FFT
    PlanPair plans;          // length 2L
    FftwArray<fftw_complex> weights;  // spectrum of w_L..w_{2L-1}, zero-padded, scaled 1/(2L)
  };
  std::vector<Level> levels;
  FftwArray<fftw_complex> work;       // L_max + 1 complex = 2 L_max + 2 doubles, in place
  std::size_t buffer_block = 0;       // L_max over the FFT levels
};

FftHistory::FftHistory(std::vector<double> weights)
    : w_(std::move(weights)), spectra_(std::make_unique<Spectra>()) {
  static_assert(std::has_single_bit(kNear), "block lengths must stay powers of two");
  if (w_.empty()) return;
  const std::size_t n_max = w_.size() - 1;  // N
  y_.reserve(w_.size());
  future_.assign(w_.size(), 0.0);

  const std::size_t near_count = std::min(kNear - 1, n_max);
  near_.resize(near_count);
  for (std::size_t i = 0; i < near_count; ++i) near_[i] = w_[near_count - i];

  // Levels L = B 2^l <= N. The first tile of a level (at step L) has the most outputs still
  // wanted, min(2L - 1, N + 1 - L); if even that one is cheaper directly, so are the rest.
  for (std::size_t block = kNear; block <= n_max; block *= 2) {
    Spectra::Level level;
    level.block = block;
    level.fft = tile_by_fft(block, std::min(2 * block - 1, n_max + 1 - block));
    if (level.fft) spectra_->buffer_block = block;
    spectra_->levels.push_back(std::move(level));
  }
  if (spectra_->buffer_block == 0) return;
  spectra_->work = fftw_array<fftw_complex>(spectra_->buffer_block + 1);
  fftw_complex* work = spectra_->work.get();
  double* real = work[0];
  for (auto& level : spectra_->levels) {
    if (!level.fft) continue;
    const std::size_t block = level.block;
    level.plans = plan_cache().get(2 * block);
    level.weights = fftw_array<fftw_complex>(block + 1);
    std::fill(real, real + 2 * block, 0.0);
    const std::size_t end = std::min(2 * block, n_max + 1);
    std::copy(w_.begin() + static_cast<std::ptrdiff_t>(block),
              w_.begin() + static_cast<std::ptrdiff_t>(end), real);
    fftw_execute_dft_r2c(level.plans.forward, real, work);
    // FFTW's transforms are unnormalised: fold 1/(2L) into the weights once.
    const double scale = 1.0 / (2.0 * static_cast<double>(block));
    for (std::size_t k = 0; k <= block; ++k) {
      level.weights[k][0] = scale * work[k][0];
      level.weights[k][1] = scale * work[k][1];
    }
  }
}

FftHistory::~FftHistory() = default;

void FftHistory::add_tile(std::size_t index, std::size_t m) {
  // Block y_{m-L}..y_{m-1} times w_L..w_{2L-1}: products land on steps n = m .. m + 2L - 2;
  // only n <= N are ever read.
  const Spectra::Level& level = spectra_->levels[index];
  const std::size_t block = level.block;
  const std::size_t outputs = std::min(2 * block - 1, future_.size() - m);
  const double* y = y_.data() + (m - block);
  double* out = future_.data() + m;
  if (!level.fft || !tile_by_fft(block, outputs)) {
    const double* w = w_.data() + block;
    for (std::size_t t = 0; t < outputs; ++t) {
      // sum over q of w_{L+q} y_{m-L+t-q}, 0 <= q < L, 0 <= t - q < L.
      const std::size_t q_lo = t >= block ? t - block + 1 : 0;
      const std::size_t q_hi = std::min(t, block - 1);
      double s = 0.0;
      for (std::size_t q = q_lo; q <= q_hi; ++q) s += w[q] * y[t - q];
      out[t] += s;
    }
    return;
  }
  fftw_complex* spectrum = spectra_->work.get();
  double* real = spectrum[0];
  std::copy(y, y + block, real);
  std::fill(real + block, real + 2 * block, 0.0);
  fftw_execute_dft_r2c(level.plans.forward, real, spectrum);
  const fftw_complex* w = level.weights.get();
  for (std::size_t k = 0; k <= block; ++k) {
    const double re = spectrum[k][0] * w[k][0] - spectrum[k][1] * w[k][1];
    const double im = spectrum[k][0] * w[k][1] + spectrum[k][1] * w[k][0];
    spectrum[k][0] = re;
    spectrum[k][1] = im;
  }
  fftw_execute_dft_c2r(level.plans.backward, spectrum, real);
  for (std::size_t t = 0; t < outputs; ++t) out[t] += real[t];
}

void FftHistory::push(double y) {
  if (y_.size() >= w_.size())
    throw std::logic_error("FftHistory: more values pushed than weights were given");
  y_.push_back(y);
  const std::size_t m = y_.size();
  if (m >= w_.size()) { lag_sum_ = 0.0; return; }  // past step N: never read

  // Every block that ends here: L divides m, for L = B, 2B, ... (a power-of-two ladder, so
  // the first L that does not divide m ends the search).
  const auto& levels = spectra_->levels;
  for (std::size_t i = 0; i < levels.size() && levels[i].block <= m && m % levels[i].block == 0; ++i)
    add_tile(i, m);

  // Near lags j = 1..min(B-1, m): near_[i] = w_{n-i} with n = near_.size(), against
  // y_{m-n+i}. Four partial sums let the compiler overlap the multiply-adds.
  const std::size_t n = near_.size();
  const std::size_t i0 = m >= n ? 0 : n - m;
  const std::size_t count = n - i0;
  const double* wp = near_.data() + i0;
  const double* yp = y_.data() + (m + i0 - n);
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::size_t i = 0;
  for (; i + 4 <= count; i += 4) {
    s0 += wp[i] * yp[i];
    s1 += wp[i + 1] * yp[i + 1];
    s2 += wp[i + 2] * yp[i + 2];
    s3 += wp[i + 3] * yp[i + 3];
  }
  for (; i < count; ++i) s0 += wp[i] * yp[i];
  lag_sum_ = future_[m] + ((s0 + s1) + (s2 + s3));
}

std::size_t FftHistory::bytes() const {
  std::size_t total = sizeof(*this) + sizeof(Spectra) +
                      (w_.capacity() + near_.capacity() + y_.capacity() + future_.capacity()) *
                          sizeof(double);
  total += spectra_->levels.capacity() * sizeof(Spectra::Level);
  for (const auto& level : spectra_->levels)
    if (level.fft) total += (level.block + 1) * sizeof(fftw_complex);
  if (spectra_->buffer_block > 0)
    total += (spectra_->buffer_block + 1) * sizeof(fftw_complex);
  return total;
}

}  // namespace adjoin

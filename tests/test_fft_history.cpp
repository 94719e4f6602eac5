// FftHistory against the direct sums (DirectHistory, and the same sums written out with
// independent partial sums for speed): the same lag sums at every step, to rounding.
//
// The difference is measured relative to sum_j |w_j| * max|y| over the weights in use, a
// bound on sum_j |w_j y_{m-j}| (the size of the terms the two engines round differently)
// that costs nothing to compute. For GL weights sum_{j>=1} |w_j| <= 1 and the lag sum itself
// is of that size for smooth data (it nearly cancels w_0 y_m), so this is not a loose scale.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "adjoin/fractional/direct_history.hpp"
#include "adjoin/fractional/fft_history.hpp"
#include "adjoin/fractional/history.hpp"
#include "adjoin/fractional/weights.hpp"

using adjoin::DirectHistory;
using adjoin::FftHistory;

namespace {

std::vector<double> smooth_sequence(std::size_t count) {
  std::vector<double> y(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(count);
    y[i] = std::sin(40.0 * t) * std::exp(-2.0 * t) + t * t;
  }
  return y;
}

std::vector<double> random_sequence(std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> y(count);
  for (auto& v : y) v = u(rng);
  return y;
}

// The lag sums sum_{j=1}^{m} w_j y_{m-j} for m = 0..N+1 (zero past N), summed as written.
// The weights are reversed so that each sum is a forward dot product, and eight partial sums
// keep the multiply-adds independent: fast enough to run for 2^16 steps many times over
// (DirectHistory's single chain of additions is several times slower).
std::vector<double> reference_lag_sums(const std::vector<double>& w, const std::vector<double>& y) {
  const std::size_t count = y.size();
  const std::size_t n = w.size();
  std::vector<double> sums(count + 1, 0.0);
  if (n == 0) return sums;
  const std::vector<double> reversed(w.rbegin(), w.rend());  // reversed[k] = w_{n-1-k}
  for (std::size_t m = 1; m < std::min(count + 1, n); ++m) {
    // sum_{i=0}^{m-1} w_{m-i} y_i, with w_{m-i} = reversed[n-1-m+i]
    const double* wp = reversed.data() + (n - 1 - m);
    const double* yp = y.data();
    double s[8] = {};
    std::size_t i = 0;
    for (; i + 8 <= m; i += 8)
      for (std::size_t k = 0; k < 8; ++k) s[k] += wp[i + k] * yp[i + k];
    for (; i < m; ++i) s[0] += wp[i] * yp[i];
    sums[m] = ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
  }
  return sums;
}

// sum_{j>=1} |w_j| * max|y|: the scale of the differences (see the top of this file).
double scale_of(const std::vector<double>& w, const std::vector<double>& y) {
  double abs_w = 0.0;
  for (std::size_t j = 1; j < w.size(); ++j) abs_w += std::abs(w[j]);
  double max_y = 0.0;
  for (double v : y) max_y = std::max(max_y, std::abs(v));
  return std::max(abs_w * max_y, 1e-300);
}

// Pushes y_0..y_N into `engine` and returns the largest difference of its lag sums from
// `expected` over all steps (including before the first push), relative to `scale`.
double max_relative_difference(adjoin::ConvolutionHistory& engine,
                               const std::vector<double>& expected, const std::vector<double>& y,
                               double scale) {
  double worst = std::abs(engine.lag_sum() - expected[0]) / scale;
  bool sizes_ok = true;
  for (std::size_t m = 0; m < y.size(); ++m) {
    engine.push(y[m]);
    sizes_ok = sizes_ok && engine.size() == m + 1;
    worst = std::max(worst, std::abs(engine.lag_sum() - expected[m + 1]) / scale);
  }
  CHECK(sizes_ok);
  return worst;
}

// FftHistory against the reference sums.
double fft_difference(const std::vector<double>& w, const std::vector<double>& y) {
  FftHistory fft(w);
  return max_relative_difference(fft, reference_lag_sums(w, y), y, scale_of(w, y));
}

}  // namespace

TEST_CASE("FftHistory equals the direct sums over 2^16 steps of GL weights", "[fft_history]") {
  constexpr std::size_t steps = std::size_t{1} << 16;
  const auto smooth = smooth_sequence(steps + 1);
  const auto noise = random_sequence(steps + 1, 7);
  for (double order : {0.01, 0.23, 0.53, 0.99}) {
    const auto w = adjoin::grunwald_letnikov_weights(order, steps + 1);
    const double d_smooth = fft_difference(w, smooth);
    const double d_noise = fft_difference(w, noise);
    INFO("order " << order << ": smooth " << d_smooth << ", random " << d_noise);
    CHECK(d_smooth < 1e-12);
    CHECK(d_noise < 1e-12);
  }
}

TEST_CASE("FftHistory equals DirectHistory step by step", "[fft_history]") {
  // The engine itself as the reference (slower, hence 2^14 steps), which also pins the
  // reference sums above to DirectHistory's semantics.
  constexpr std::size_t steps = std::size_t{1} << 14;
  for (double order : {0.01, 0.23, 0.53, 0.99})
    for (const auto& y : {smooth_sequence(steps + 1), random_sequence(steps + 1, 3)}) {
      const auto w = adjoin::grunwald_letnikov_weights(order, steps + 1);
      DirectHistory direct(w);
      FftHistory fft(w);
      const double scale = scale_of(w, y);
      double worst = 0.0, worst_reference = 0.0;
      const auto reference = reference_lag_sums(w, y);
      for (std::size_t m = 0; m < y.size(); ++m) {
        direct.push(y[m]);
        fft.push(y[m]);
        worst = std::max(worst, std::abs(fft.lag_sum() - direct.lag_sum()) / scale);
        worst_reference =
            std::max(worst_reference, std::abs(reference[m + 1] - direct.lag_sum()) / scale);
      }
      INFO("order " << order << ": fft vs direct " << worst << ", reference vs direct "
                    << worst_reference);
      CHECK(worst < 1e-12);
      CHECK(worst_reference < 1e-13);
    }
}

TEST_CASE("FftHistory: lengths that are not powers of two, and tiny ones", "[fft_history]") {
  // N + 1 weights for N in a spread of awkward values: below, at and just past the near-lag
  // width and the level boundaries.
  const std::size_t b = FftHistory::near_lags();
  for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{3}, b - 2,
                        b - 1, b, b + 1, 2 * b - 1, 2 * b + 1, 4 * b + 3, std::size_t{1000},
                        std::size_t{4097}, std::size_t{12345}, std::size_t{65537}}) {
    const auto w = adjoin::grunwald_letnikov_weights(0.37, n + 1);
    const double d = fft_difference(w, random_sequence(n + 1, static_cast<unsigned>(n)));
    INFO("N = " << n << ": max relative difference " << d);
    CHECK(d < 1e-12);
  }
}

TEST_CASE("FftHistory: the last windows of each level, cut short at N", "[fft_history]") {
  // Near N a level's last window or two want fewer than 2L - 1 outputs, and are formed
  // directly, by a shorter FFT of just the values that reach them, or in full, by a cost
  // estimate. N = j L + d for the first three block lengths L and a spread of d covers all
  // three (and windows with fewer partitions than r - 1 at the top level). Random weights:
  // every tile counts equally.
  const std::size_t b = FftHistory::near_lags(), r = FftHistory::level_ratio();
  std::size_t cases = 0;
  for (std::size_t block : {b, r * b, r * r * b})
    for (std::size_t j : {std::size_t{1}, std::size_t{2}, r - 1, r})
      for (std::size_t d : {std::size_t{1}, std::size_t{3}, block / 16, block / 3, block - 1,
                            block + 5, block + block / 2}) {
        const std::size_t n = j * block + d;
        if (n > 40000) continue;  // the reference is quadratic
        const auto w = random_sequence(n + 1, static_cast<unsigned>(n));
        const double diff = fft_difference(w, random_sequence(n + 1, static_cast<unsigned>(n + 1)));
        INFO("N = " << n << " (L = " << block << "): max relative difference " << diff);
        CHECK(diff < 1e-12);
        ++cases;
      }
  CHECK(cases > 50);
}

TEST_CASE("FftHistory: arbitrary weights and exact small cases", "[fft_history]") {
  // Random (non-decaying) weights exercise every tile equally.
  const auto w = random_sequence(30001, 11);
  CHECK(fft_difference(w, random_sequence(30001, 12)) < 1e-12);

  // N = 3 by hand: lag sums 0, w1 y0, w1 y1 + w2 y0, w1 y2 + w2 y1 + w3 y0, then 0.
  FftHistory h({1.0, 2.0, 3.0, 4.0});
  CHECK(h.lag_sum() == 0.0);
  h.push(1.0);
  CHECK(h.lag_sum() == 2.0);
  h.push(10.0);
  CHECK(h.lag_sum() == 23.0);
  h.push(100.0);
  CHECK(h.lag_sum() == 234.0);
  h.push(1000.0);
  CHECK(h.lag_sum() == 0.0);
  CHECK(h.size() == 4);
  CHECK_THROWS_AS(h.push(1.0), std::logic_error);

  FftHistory empty({});
  CHECK(empty.lag_sum() == 0.0);
  CHECK_THROWS_AS(empty.push(1.0), std::logic_error);
}

TEST_CASE("FftHistory: independent instances in parallel threads", "[fft_history]") {
  // Sweeps run simulations in threads: planning (first use of each length) and execution must
  // be safe. Distinct lengths make the threads plan different transforms at the same time.
  const std::vector<std::size_t> lengths{5000, 7000, 9000, 11000, 13000, 20000};
  std::vector<double> results(lengths.size(), 1.0);
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < lengths.size(); ++k)
    threads.emplace_back([&, k] {
      const auto w = adjoin::grunwald_letnikov_weights(0.3 + 0.1 * static_cast<double>(k),
                                                       lengths[k] + 1);
      const auto y = random_sequence(lengths[k] + 1, static_cast<unsigned>(k));
      const auto expected = reference_lag_sums(w, y);
      FftHistory fft(w);
      double worst = 0.0;
      for (std::size_t m = 0; m < y.size(); ++m) {
        fft.push(y[m]);
        worst = std::max(worst, std::abs(fft.lag_sum() - expected[m + 1]));
      }
      results[k] = worst / scale_of(w, y);
    });
  for (auto& t : threads) t.join();
  for (std::size_t k = 0; k < lengths.size(); ++k) {
    INFO("N = " << lengths[k] << ": " << results[k]);
    CHECK(results[k] < 1e-12);
  }
}

TEST_CASE("make_history builds the FFT engine", "[fft_history]") {
  auto h = adjoin::make_history(adjoin::HistoryEngine::fft, {1.0, -0.5, -0.125});
  REQUIRE(dynamic_cast<FftHistory*>(h.get()) != nullptr);
  h->push(2.0);
  CHECK(h->lag_sum() == -1.0);
}

TEST_CASE("FftHistory over 2^20 steps: the direct sums at sampled steps, and memory linear in the steps", "[fft_history]") {
  // Two rods' histories over 2^20 steps, as in a long simulation, with a feedback loop so each
  // value depends on the previous lag sums. (Its speed is measured in bench/bench_history, not
  // here.) At sampled steps the lag sum is recomputed directly from the pushed values.
  constexpr std::size_t steps = std::size_t{1} << 20;
  const auto w1 = adjoin::grunwald_letnikov_weights(0.23, steps + 1);
  const auto w2 = adjoin::grunwald_letnikov_weights(0.53, steps + 1);
  FftHistory h1(w1), h2(w2);
  std::vector<double> y1s, y2s;
  y1s.reserve(steps + 1);
  y2s.reserve(steps + 1);
  const auto direct = [](const std::vector<double>& w, const std::vector<double>& ys) {
    double sum = 0.0;  // sum_{j=1}^{m} w_j y_{m-j}, m = ys.size()
    for (std::size_t j = 1; j <= ys.size(); ++j) sum += w[j] * ys[ys.size() - j];
    return sum;
  };
  double largest = 0.0;
  for (std::size_t m = 0; m <= steps; ++m) {
    const double t = static_cast<double>(m) * 1e-4;
    const double y1 = std::sin(t) - 0.1 * h1.lag_sum();
    const double y2 = std::cos(t) - 0.1 * h2.lag_sum() + 0.01 * y1;
    h1.push(y1);
    h2.push(y2);
    y1s.push_back(y1);
    y2s.push_back(y2);
    if (m == 1000 || m == 65537 || m == 333333 || m == steps - 1) {
      const double d1 = direct(w1, y1s), d2 = direct(w2, y2s);
      largest = std::max({largest, std::abs(h1.lag_sum() - d1) / (1.0 + std::abs(d1)),
                          std::abs(h2.lag_sum() - d2) / (1.0 + std::abs(d2))});
    }
  }
  INFO("largest relative difference from the direct sums " << largest << "; bytes per step "
                                                            << static_cast<double>(h1.bytes()) / static_cast<double>(steps));
  CHECK(largest < 1e-11);
  // O(N) memory: a fixed number of doubles per step.
  CHECK(static_cast<double>(h1.bytes()) / static_cast<double>(steps) < 128.0);
}

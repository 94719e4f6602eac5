// observe/peak_table.hpp: the peaks of many signals in arrays are SmoothPeak's and Peak's, bit
// for bit (the run observer's peaks of every channel rest on it).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "adjoin/observe/peak_table.hpp"

using namespace adjoin;

TEST_CASE("PeakTable gives SmoothPeak's and Peak's peaks and times bit for bit", "[peaks]") {
  // 11 signals, the first 0, 3, 5 or 11 refined (the two- and four-at-a-time passes and their
  // tails), on the SSE2 path and on the AVX path where the CPU has it, over oscillations with
  // growing and falling amplitude, sign changes, plateaus and a zero signal.
  for (bool avx : {false, true})
  for (std::size_t smooth : {std::size_t{0}, std::size_t{3}, std::size_t{5}, std::size_t{11}}) {
    const std::size_t n = 11;
    PeakTable table;
    table.reset(smooth, n, avx);
    std::vector<SmoothPeak> smooth_peaks(n);
    std::vector<Peak> sampled_peaks(n);
    std::mt19937 random(42);
    std::uniform_real_distribution<double> noise(-0.05, 0.05);
    const double h = 0.01;
    for (int step = 0; step <= 3000; ++step) {
      const double t = step * h;
      double* row = table.row();
      for (std::size_t k = 0; k < n; ++k) {
        const double envelope = 1.0 + std::sin(0.013 * step * static_cast<double>(k + 1));
        double y = envelope * std::sin(0.7 * t * static_cast<double>(k + 1) + static_cast<double>(k)) + noise(random);
        if (k == 2 && step % 400 < 100) y = 1.7;  // a plateau at a new peak
        if (k == 5) y = 0.0;
        row[k] = y;
        if (k < smooth) smooth_peaks[k].update(y, t);
        else sampled_peaks[k].update(y, t);
      }
      table.update(t);
      for (std::size_t k = 0; k < n; ++k) CHECK(table.last()[k] == row[k]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const Peak expected = k < smooth ? smooth_peaks[k].peak() : sampled_peaks[k];
      INFO("avx " << avx << ", smooth " << smooth << ", signal " << k);
      CHECK(table.peak(k).max_abs == expected.max_abs);
      CHECK(table.peak(k).t == expected.t);
    }
    CHECK(table.peak(5).max_abs == 0.0);
    CHECK(table.peak(0).max_abs > 1.0);
  }
}

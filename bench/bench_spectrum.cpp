// Response spectra: cost of the exact recursion with sub-steps and turning-point search.
//
//   build/bench/bench_spectrum
//   build/bench/bench_spectrum --benchmark_filter=Record12000
//
// Record12000: 12,000 samples of Chi-Chi TCU122-N (dt = 0.005 s, 60 s; the record's first
// 12,000 of 18,000 samples) at the default 100 log-spaced periods 0.01-10 s, 5 % damping, on
// one thread and on all cores. Scaling: synthetic filtered noise (dt = 0.005 s) at
// 3,000/12,000/48,000 samples x 25/100/400 periods (same 0.01-10 s range), one thread; the
// counter ns_per_sample_period should stay flat if the cost is linear in samples x periods.
// KonnoOhmachi: smoothing a record's Fourier amplitudes (below).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "adjoin/ground/record_file.hpp"
#include "adjoin/post/intensity.hpp"
#include "adjoin/post/spectrum.hpp"

namespace {

std::vector<double> chichi_12000() {
  static const std::vector<double> accel = [] {
    const auto path = std::filesystem::path(ADJOIN_REAL_RECORDS) / "peer" / "RSN1546_CHICHI_TCU122-N.AT2";
    adjoin::Record record = adjoin::read_record(path);
    record.accel.resize(12000);
    return record.accel;
  }();
  return accel;
}

// Reproducible noise through a 2-pole filter (f0 = 2.5 Hz, zeta 0.6), with a smooth envelope.
std::vector<double> synthetic(std::size_t n) {
  std::vector<double> accel(n);
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  const double dt = 0.005, w = 2.0 * 3.141592653589793 * 2.5, z = 0.6;
  double x = 0.0, v = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const double noise = static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5;
    const double a = noise * 400.0 - 2.0 * z * w * v - w * w * x;
    v += a * dt;
    x += v * dt;
    const double t = static_cast<double>(i) / static_cast<double>(n);
    accel[i] = (2.0 * z * w * v + w * w * x) * std::sin(3.141592653589793 * t);
  }
  return accel;
}

void run(benchmark::State& state, const std::vector<double>& accel, const adjoin::SpectrumOptions& options) {
  const std::size_t periods = options.periods.empty() ? 100 : options.periods.size();
  for (auto _ : state) {
    adjoin::ResponseSpectrum s = adjoin::response_spectrum(0.005, accel, options);
    benchmark::DoNotOptimize(s.values.data());
  }
  const double work = static_cast<double>(accel.size()) * static_cast<double>(periods);
  state.counters["samples"] = static_cast<double>(accel.size());
  state.counters["periods"] = static_cast<double>(periods);
  // time / (iterations x work x 1e-9): nanoseconds per (sample x period).
  state.counters["ns_per_sample_period"] =
      benchmark::Counter(work * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void Record12000(benchmark::State& state) {
  adjoin::SpectrumOptions options;
  options.threads = static_cast<unsigned>(state.range(0));  // 0: all cores
  options.refine_peaks = state.range(1) != 0;
  run(state, chichi_12000(), options);
}
BENCHMARK(Record12000)
    ->ArgNames({"threads", "refine"})
    ->Args({1, 1})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void Scaling(benchmark::State& state) {
  adjoin::SpectrumOptions options;
  options.threads = 1;
  options.periods = adjoin::period_range(0.01, 10.0, static_cast<std::size_t>(state.range(1)), adjoin::PeriodSpacing::log);
  run(state, synthetic(static_cast<std::size_t>(state.range(0))), options);
}
BENCHMARK(Scaling)
    ->ArgNames({"samples", "periods"})
    ->Args({3000, 100})
    ->Args({12000, 100})
    ->Args({48000, 100})
    ->Args({12000, 25})
    ->Args({12000, 400})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Konno-Ohmachi smoothing (post/intensity.hpp) of the whole Chi-Chi record's Fourier
// amplitudes (18,000 samples: 9,001 frequencies) at 200 log-spaced centres, b = 40: the
// direct sum costs centres x frequencies, reported per product.
void KonnoOhmachi(benchmark::State& state) {
  const auto path = std::filesystem::path(ADJOIN_REAL_RECORDS) / "peer" / "RSN1546_CHICHI_TCU122-N.AT2";
  const adjoin::FourierSpectrum fas = adjoin::fourier_amplitude_spectrum(adjoin::read_record(path));
  const std::vector<double> centres = adjoin::period_range(0.1, 50.0, 200, adjoin::PeriodSpacing::log);
  for (auto _ : state) {
    std::vector<double> smoothed = adjoin::konno_ohmachi(fas, centres, 40.0);
    benchmark::DoNotOptimize(smoothed.data());
  }
  state.counters["ns_per_product"] = benchmark::Counter(
      static_cast<double>(fas.frequency.size() - 1) * static_cast<double>(centres.size()) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(KonnoOhmachi)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();

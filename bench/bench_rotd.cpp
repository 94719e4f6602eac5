// Orientation-independent (RotD) and inelastic spectra: cost against the single elastic spectrum.
//
//   build/bench/bench_rotd --benchmark_filter='Pair|Single'
//   build/bench/bench_rotd --benchmark_filter=Ductility
//
// Pair: RotD00/50/100 (and GMRotI50) of the Chino Hills RSN8883 pair (90 and 360 degrees,
// 16,396 samples at dt = 0.005 s) at the default 100 log-spaced periods 0.01-10 s, 5 %, one
// thread, exact peaks (refine = 1) or peaks at the sub-step points (refine = 0).
// Single: the single-component spectrum of the 90-degree component, same periods, one thread.
// The ratio Pair / Single says what the pair costs in single spectra (two oscillators per
// period plus the rotations).
// Ductility: constant-ductility spectra (EPP, 5 %) at 100 periods x 6 ductilities
// (1, 1.5, 2, 3, 4, 6) of Chi-Chi TCU122-N's first 12,000 samples (dt = 0.005 s), one thread
// and all cores.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <vector>

#include "adjoin/ground/record_file.hpp"
#include "adjoin/post/inelastic.hpp"
#include "adjoin/post/rotd.hpp"
#include "adjoin/post/spectrum.hpp"

namespace {

const adjoin::Record& rsn8883(int component) {
  static const adjoin::Record h1 = adjoin::read_record(std::filesystem::path(ADJOIN_REAL_RECORDS) / "peer" /
                                                       "RSN8883_14383980_13849090.AT2");
  static const adjoin::Record h2 = adjoin::read_record(std::filesystem::path(ADJOIN_REAL_RECORDS) / "peer" /
                                                       "RSN8883_14383980_13849360.AT2");
  return component == 1 ? h1 : h2;
}

const std::vector<double>& chichi_12000() {
  static const std::vector<double> accel = [] {
    adjoin::Record record =
        adjoin::read_record(std::filesystem::path(ADJOIN_REAL_RECORDS) / "peer" / "RSN1546_CHICHI_TCU122-N.AT2");
    record.accel.resize(12000);
    return record.accel;
  }();
  return accel;
}

void Pair(benchmark::State& state) {
  adjoin::RotDOptions options;
  options.threads = 1;
  options.refine_peaks = state.range(0) != 0;
  for (auto _ : state) {
    adjoin::RotDSpectrum s = adjoin::rotd_spectrum(rsn8883(1), rsn8883(2), options);
    benchmark::DoNotOptimize(s.values.data());
  }
  state.counters["samples"] = static_cast<double>(rsn8883(1).accel.size());
}
BENCHMARK(Pair)->ArgNames({"refine"})->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void Single(benchmark::State& state) {
  adjoin::SpectrumOptions options;
  options.threads = 1;
  options.refine_peaks = state.range(0) != 0;
  for (auto _ : state) {
    adjoin::ResponseSpectrum s = adjoin::response_spectrum(rsn8883(1), options);
    benchmark::DoNotOptimize(s.values.data());
  }
}
BENCHMARK(Single)->ArgNames({"refine"})->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void Ductility(benchmark::State& state) {
  adjoin::InelasticOptions options;
  options.threads = static_cast<unsigned>(state.range(0));
  options.ductilities = {1.0, 1.5, 2.0, 3.0, 4.0, 6.0};
  for (auto _ : state) {
    adjoin::InelasticSpectrum s = adjoin::constant_ductility_spectrum(0.005, chichi_12000(), options);
    benchmark::DoNotOptimize(s.values.data());
  }
}
BENCHMARK(Ductility)->ArgNames({"threads"})->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();

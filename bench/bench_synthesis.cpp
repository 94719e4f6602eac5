// Synthetic ground motion: cost of the filtered-noise synthesis and of spectrum matching.
//
//   build/bench/bench_synthesis
//   build/bench/bench_synthesis --benchmark_filter=Synthesize
//
// Synthesize/CloughPenzien60s: 60 s at dt = 0.005 s (12,001 samples, FFT length 12,096),
// Clough-Penzien spectrum, Jennings-Housner-Tsai envelope, scaled to a target PGA (target:
// <= 5 ms). Synthesize/Stationary60s: the same without envelope and scaling. The first call
// makes the FFTW plan; later calls reuse it, as in a sweep.
// Match/EC8B_25s: synthesize_matched to EC8 type 1 ground B (ag 0.25 g), 100 periods in
// 0.1-3 s, +-10 %, 25 s at 0.005 s; counters give the iterations and the final max misfit.
#include <benchmark/benchmark.h>

#include "adjoin/post/spectrum_matching.hpp"
#include "adjoin/ground/synthesis.hpp"

namespace {

void Synthesize(benchmark::State& state, adjoin::EnvelopeKind envelope, bool scale) {
  adjoin::SynthesisOptions o;
  o.spectrum = adjoin::SpectrumModel::clough_penzien;
  o.duration = 60.0;
  o.dt = 0.005;
  o.envelope.kind = envelope;
  if (scale)
    o.target_pga = 0.3;
  else
    o.s0 = 0.01;
  std::uint64_t seed = 1;
  for (auto _ : state) {
    o.seed = seed++;
    adjoin::Record r = adjoin::synthesize(o);
    benchmark::DoNotOptimize(r.accel.data());
  }
  state.counters["samples"] = 12001;
}
BENCHMARK_CAPTURE(Synthesize, CloughPenzien60s, adjoin::EnvelopeKind::jennings_housner_tsai, true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Synthesize, Stationary60s, adjoin::EnvelopeKind::none, false)->Unit(benchmark::kMillisecond);

void Match(benchmark::State& state) {
  adjoin::SynthesisOptions o;
  o.duration = 25.0;
  o.dt = 0.005;
  adjoin::MatchOptions m;
  m.target = adjoin::TargetSpectrum::ec8('B', 0.25);
  adjoin::MatchReport report;
  std::uint64_t seed = 1;
  double iterations = 0, misfit = 0, runs = 0;
  for (auto _ : state) {
    o.seed = seed++;
    adjoin::Record r = adjoin::synthesize_matched(o, m, &report);
    benchmark::DoNotOptimize(r.accel.data());
    iterations += report.iterations;
    misfit += report.max_misfit;
    runs += 1;
  }
  state.counters["iterations"] = iterations / runs;
  state.counters["max_misfit"] = misfit / runs;
}
BENCHMARK(Match)->Name("Match/EC8B_25s")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

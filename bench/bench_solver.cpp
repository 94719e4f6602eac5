// Whole-run cost of the solver on the paper's scenes, by scheme, history engine and step.
//
//     build/bench/bench_solver                                  # everything (about a minute)
//     build/bench/bench_solver --benchmark_filter=targets       # the targets only
//
// Counters: steps/s, and history bytes per step (what the history engines hold).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"

namespace {

adjoin::Scene scene(const char* which, std::vector<std::string> overrides) {
  overrides.push_back("output.timeseries=false");
  return adjoin::load_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-" + which + ".toml", overrides);
}

std::string exact(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

void run(benchmark::State& state, const adjoin::Scene& s) {
  std::size_t bytes = 0;
  for (auto _ : state) {
    const auto report = adjoin::run(s);
    bytes = report.solver.history_bytes;
    benchmark::DoNotOptimize(report.peak("A.x1").max_abs);
  }
  const double steps = static_cast<double>(s.solver.steps());
  state.counters["steps/s"] = benchmark::Counter(steps, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes/step"] = static_cast<double>(bytes) / steps;
}

// ---- the targets of the solver issue ----
// The paper's own run: paper scheme, h = 0.002 (8000 steps).
void BM_paper_at_paper_h(benchmark::State& st) { run(st, scene("strong", {"solver.scheme=paper", "solver.h=0.002"})); }
BENCHMARK(BM_paper_at_paper_h)->Name("targets/strong/paper/direct/h:0.002")->Unit(benchmark::kMillisecond);
// The paper's accuracy with the default scheme (its errors at h = 0.008 are below the paper
// run's: see `adjoin converge records/scenes/paper-strong.toml`).
void BM_strong_paper_accuracy(benchmark::State& st) { run(st, scene("strong", {"solver.scheme=implicit", "solver.h=0.008"})); }
BENCHMARK(BM_strong_paper_accuracy)->Name("targets/strong/implicit/direct/h:0.008")->Unit(benchmark::kMillisecond);
// Relative error <= 1e-4 in max|x1|, min gap and friction energy.
void BM_strong_1e4(benchmark::State& st) { run(st, scene("strong", {"solver.scheme=implicit", "solver.h=0.004"})); }
BENCHMARK(BM_strong_1e4)->Name("targets/strong/implicit/direct/h:0.004")->Unit(benchmark::kMillisecond);
// 2^20 steps of the strong scene with the fft engine, and with soe.
void strong_2e20(benchmark::State& st, const char* engine) {
  char h[32];
  std::snprintf(h, sizeof h, "%.17g", 16.0 / (1 << 20));  // exactly 2^20 steps
  run(st, scene("strong", {"solver.scheme=implicit", std::string("solver.history=\"") + engine + "\"", std::string("solver.h=") + h}));
}
void BM_strong_2e20(benchmark::State& st) { strong_2e20(st, "fft"); }
void BM_strong_2e20_soe(benchmark::State& st) { strong_2e20(st, "soe"); }
BENCHMARK(BM_strong_2e20)->Name("targets/strong/implicit/fft/steps:2^20")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_strong_2e20_soe)->Name("targets/strong/implicit/soe/steps:2^20")->Unit(benchmark::kMillisecond)->Iterations(3);
// The weak scene to 1e-9 in x(16): h = 0.0008 (see tests/test_weak_exact.cpp).
void BM_weak_1e9(benchmark::State& st) {
  run(st, scene("weak", {"solver.scheme=implicit", "solver.history=\"fft\"", "solver.h=0.0008"}));
}
BENCHMARK(BM_weak_1e9)->Name("targets/weak/implicit/fft/h:0.0008")->Unit(benchmark::kMillisecond);

// ---- steps per second and bytes per step, by scheme and engine ----
void BM_ladder(benchmark::State& st, const char* scheme, const char* engine) {
  const double steps = static_cast<double>(st.range(0));
  run(st, scene("strong", {std::string("solver.scheme=") + scheme, std::string("solver.history=\"") + engine + "\"",
                           "solver.h=" + exact(16.0 / steps)}));
}
BENCHMARK_CAPTURE(BM_ladder, paper_direct, "paper", "direct")->RangeMultiplier(4)->Range(1 << 12, 1 << 16)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ladder, implicit_direct, "implicit", "direct")->RangeMultiplier(4)->Range(1 << 12, 1 << 16)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ladder, paper_fft, "paper", "fft")->RangeMultiplier(4)->Range(1 << 12, 1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ladder, implicit_fft, "implicit", "fft")->RangeMultiplier(4)->Range(1 << 12, 1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ladder, implicit_gl_fft, "implicit-gl", "fft")->RangeMultiplier(4)->Range(1 << 12, 1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ladder, paper_soe, "paper", "soe")->RangeMultiplier(4)->Range(1 << 12, 1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ladder, implicit_soe, "implicit", "soe")->RangeMultiplier(4)->Range(1 << 12, 1 << 20)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

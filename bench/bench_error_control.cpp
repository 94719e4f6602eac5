// The cost of error control on the paper's strong scene (implicit scheme, fft history):
//
//     build/bench/bench_error_control
//
// For each tolerance (1e-6, 1e-9): "plain" is one run at the step the tolerance run chose,
// "estimated" the same run with its error estimate (the companion at 2h), "tolerance" the whole
// run to the tolerance (its ladder of rungs, their estimates, the kept run). The budget:
// tolerance / plain <= 1.6. Counters: h, the rungs tried, and the estimated peak error.
#include <benchmark/benchmark.h>

#include <string>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/error_estimate.hpp"
#include "adjoin/study/run.hpp"

namespace {

adjoin::Scene strong() {
  return adjoin::load_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml",
                            {"solver.scheme=implicit", "solver.history=fft", "output.timeseries=false"});
}

// The step the tolerance run picks (computed once per tolerance, outside the timing).
adjoin::Scene at_chosen_h(double tolerance, adjoin::TolerantRun* chosen) {
  adjoin::Scene s = strong();
  *chosen = adjoin::run_to_tolerance(s, tolerance);
  s.solver.h = chosen->h;
  return s;
}

void counters(benchmark::State& state, const adjoin::TolerantRun& t) {
  state.counters["h"] = t.h;
  state.counters["rungs"] = static_cast<double>(t.ladder.size());
  state.counters["est_rel_peak_err"] = t.estimate.max_relative_peak;
}

void BM_plain(benchmark::State& state, double tolerance) {
  adjoin::TolerantRun t;
  const adjoin::Scene s = at_chosen_h(tolerance, &t);
  for (auto _ : state) benchmark::DoNotOptimize(adjoin::run(s).peak("A.x1").max_abs);
  counters(state, t);
}

void BM_estimated(benchmark::State& state, double tolerance) {
  adjoin::TolerantRun t;
  const adjoin::Scene s = at_chosen_h(tolerance, &t);
  for (auto _ : state) {
    const auto r = adjoin::run(s);
    benchmark::DoNotOptimize(adjoin::estimate_error(s, r).max_relative_peak);
  }
  counters(state, t);
}

void BM_tolerance(benchmark::State& state, double tolerance) {
  const adjoin::Scene s = strong();
  for (auto _ : state) benchmark::DoNotOptimize(adjoin::run_to_tolerance(s, tolerance).h);
  counters(state, adjoin::run_to_tolerance(s, tolerance));
}

}  // namespace

BENCHMARK_CAPTURE(BM_plain, tol_1e-6, 1e-6)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_estimated, tol_1e-6, 1e-6)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_tolerance, tol_1e-6, 1e-6)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_plain, tol_1e-9, 1e-9)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_estimated, tol_1e-9, 1e-9)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_tolerance, tol_1e-9, 1e-9)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

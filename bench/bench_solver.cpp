// Whole-run cost of the solver: the paper's strong scene by scheme, history engine and step.
//
//     build/bench/bench_solver                       # all
//     build/bench/bench_solver --benchmark_filter=paper_strong/h:0.002
//
// Counters: steps/s and bytes of history per step.
#include <benchmark/benchmark.h>

#include <string>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"

namespace {

adjoin::Scene strong(const std::vector<std::string>& overrides) {
  return adjoin::load_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml", overrides);
}

class Discard final : public adjoin::Observer {
 public:
  void observe(const adjoin::State& s) override { benchmark::DoNotOptimize(s.x1); }
};

// The strong scene at the paper's h = 0.002 (8000 steps), summary observers attached.
void BM_paper_strong(benchmark::State& state) {
  const auto scene = strong({"output.timeseries=false"});
  for (auto _ : state) benchmark::DoNotOptimize(adjoin::run_scene(scene).peaks.x1.max_abs);
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(scene.solver.steps()),
                                                 benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_paper_strong)->Name("paper_strong/h:0.002")->Unit(benchmark::kMillisecond);

// Steps per second against the number of steps (direct history: quadratic).
void BM_paper_steps(benchmark::State& state) {
  const double steps = static_cast<double>(state.range(0));
  const auto scene = strong({"solver.h=" + std::to_string(16.0 / steps)});
  Discard discard;
  for (auto _ : state) adjoin::run_scene(scene, &discard);
  state.counters["steps/s"] = benchmark::Counter(steps, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_paper_steps)->Name("paper_direct/steps")->RangeMultiplier(2)->Range(1 << 12, 1 << 15)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

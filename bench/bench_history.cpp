// History engines: a whole run of N + 1 steps (construction, then push and lag_sum each step)
// for GL weights of order 0.53, direct against fft against soe (tolerance 1e-12; its
// compression is made once per process and shared, so it is made before the timing).
//
//   build/bench/bench_history                              all sizes (direct up to 2^17)
//   build/bench/bench_history --benchmark_filter=fft       the fast engine only
//   build/bench/bench_history --benchmark_filter='(fft|soe)/(16384|262144|4194304)$'   fft against soe
//   build/bench/bench_history --benchmark_filter='fft/(1048576|1066667)$'   the solver's size
//   build/bench/bench_history --benchmark_filter=40          40 histories: one bank against 40 apart
//
// Counters: time_per_step (s) = run time / N; bytes_per_step = bytes() / N. The direct engine
// is quadratic (2^20 steps take over ten minutes), so it is registered up to 2^17 only; set
// ADJOIN_BENCH_DIRECT_2E20=1 to add one direct run of 2^20 steps.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <cstddef>
#include <memory>
#include <vector>

#include "adjoin/fractional/history.hpp"
#include "adjoin/fractional/history_set.hpp"
#include "adjoin/fractional/soe_history.hpp"
#include "adjoin/fractional/weights.hpp"

namespace {

void run(benchmark::State& state, adjoin::HistoryEngine engine) {
  const auto steps = static_cast<std::size_t>(state.range(0));
  const bool soe = engine == adjoin::HistoryEngine::soe;
  const std::vector<double> weights = soe ? std::vector<double>{} : adjoin::grunwald_letnikov_weights(0.53, steps + 1);
  if (soe) adjoin::soe_compression(adjoin::WeightRule::grunwald_letnikov, 0.53, 1e-12, steps + 1);
  // The input as a table, as in run_many: a sine per step (15 to 25 ns) would be timed with the
  // engine (the soe engine's own step is of that order).
  std::vector<double> input(1024);
  for (std::size_t i = 0; i < input.size(); ++i) input[i] = std::sin(1e-2 * static_cast<double>(i));
  std::size_t bytes = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::vector<double> w = weights;  // the engine takes ownership; copying is not timed
    state.ResumeTiming();
    auto history = soe ? adjoin::make_history(engine, adjoin::WeightRule::grunwald_letnikov, 0.53, steps + 1, 1e-12)
                       : adjoin::make_history(engine, std::move(w));
    // A feedback loop, like a rod: each value depends on the previous lag sum.
    double y = 0.0;
    for (std::size_t m = 0; m <= steps; ++m) {
      y = input[m & 1023] - 0.1 * history->lag_sum();
      history->push(y);
    }
    benchmark::DoNotOptimize(y);
    bytes = history->bytes();
    state.PauseTiming();
    history.reset();  // freeing is not timed
    state.ResumeTiming();
  }
  state.counters["time_per_step"] = benchmark::Counter(
      static_cast<double>(steps), benchmark::Counter::kIsIterationInvariantRate |
                                      benchmark::Counter::kInvert);
  state.counters["bytes_per_step"] =
      static_cast<double>(bytes) / static_cast<double>(steps);
}

// 40 histories of order 0.53 stepped together, as the 2 x 20 Zener pair's (a HistorySet, history_set.hpp, banked by soe_bank.hpp), against
// 40 SoeHistories: time_per_element_step = run time / (N * 40).
void run_many(benchmark::State& state, bool bank) {
  const auto steps = static_cast<std::size_t>(state.range(0));
  constexpr std::size_t kMembers = 40;
  adjoin::soe_compression(adjoin::WeightRule::grunwald_letnikov, 0.53, 1e-12, steps + 1);
  const std::vector<double> orders(kMembers, 0.53);
  std::vector<double> input(1024);  // (a table: 40 sines a step would cost more than the histories)
  for (std::size_t i = 0; i < input.size(); ++i) input[i] = std::sin(1e-2 * static_cast<double>(i));
  std::vector<double> y_all(kMembers);
  for (auto _ : state) {
    if (bank) {  // (the structure stepper's way: all lag sums read, all values given at once)
      adjoin::HistorySet set(adjoin::HistoryEngine::soe, adjoin::WeightRule::grunwald_letnikov, orders, steps + 1, 1e-12);
      for (std::size_t m = 0; m <= steps; ++m) {
        for (std::size_t e = 0; e < kMembers; ++e) y_all[e] = input[(m + e) & 1023] - 0.1 * set.lag_sums()[e];
        set.push(y_all.data());
      }
      benchmark::DoNotOptimize(y_all.data());
      state.PauseTiming();
      set = adjoin::HistorySet();
      state.ResumeTiming();
      continue;
    }
    std::vector<std::unique_ptr<adjoin::ConvolutionHistory>> histories;
    for (std::size_t e = 0; e < kMembers; ++e)
      histories.push_back(adjoin::make_history(adjoin::HistoryEngine::soe, adjoin::WeightRule::grunwald_letnikov, 0.53, steps + 1, 1e-12));
    double y = 0.0;
    for (std::size_t m = 0; m <= steps; ++m)
      for (std::size_t e = 0; e < kMembers; ++e) {
        y = input[(m + e) & 1023] - 0.1 * histories[e]->lag_sum();
        histories[e]->push(y);
      }
    benchmark::DoNotOptimize(y);
    state.PauseTiming();
    histories.clear();
    state.ResumeTiming();
  }
  state.counters["time_per_element_step"] = benchmark::Counter(
      static_cast<double>(steps * kMembers), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_direct(benchmark::State& state) { run(state, adjoin::HistoryEngine::direct); }
void BM_soe_bank40(benchmark::State& state) { run_many(state, true); }
void BM_soe_alone40(benchmark::State& state) { run_many(state, false); }
void BM_fft(benchmark::State& state) { run(state, adjoin::HistoryEngine::fft); }
void BM_soe(benchmark::State& state) { run(state, adjoin::HistoryEngine::soe); }

}  // namespace

BENCHMARK(BM_direct)->RangeMultiplier(2)->Range(1 << 12, 1 << 17)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_fft)->RangeMultiplier(2)->Range(1 << 12, 1 << 22)->Unit(benchmark::kMillisecond);
// The length bench_solver's "2^20 steps" target really runs (its h = 16 / 2^20 is printed as
// 0.000015, so 1,066,667 steps): not a power of two, so the last windows of each level are
// cut short, as in most runs.
BENCHMARK(BM_fft)->Arg(1066667)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_soe)->RangeMultiplier(2)->Range(1 << 12, 1 << 22)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_soe_bank40)->RangeMultiplier(4)->Range(1 << 14, 1 << 22)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_soe_alone40)->RangeMultiplier(4)->Range(1 << 14, 1 << 22)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  if (const char* flag = std::getenv("ADJOIN_BENCH_DIRECT_2E20"); flag != nullptr && *flag == '1')
    benchmark::RegisterBenchmark("BM_direct/1048576", BM_direct)
        ->Arg(1 << 20)
        ->Iterations(1)
        ->Unit(benchmark::kSecond);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// Sweep throughput: a 1,000-run sweep of the paper's strong scene (h = 0.002, t_end = 16, slip
// force mu from 0 to 1) with the paper and the implicit scheme, each with the direct and the fft
// history engine, on 1 and 2 threads. Reports runs/s, and for 2 threads the parallel efficiency
// (runs/s on 2 threads) / (2 x runs/s on 1 thread) against the 1-thread benchmark just before.
//
//     build/bench/bench_sweep                                # everything (a few minutes)
//     build/bench/bench_sweep --benchmark_filter=fft         # the fast history engine only
//
// Target: >= 200 runs/s (docs/explanation/benchmarks.md quotes the figures measured).
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>
#include <map>
#include <string>

#include "adjoin/io/sweep_file.hpp"

namespace {

const char* kSchemes[] = {"paper", "implicit"};
const char* kHistories[] = {"direct", "fft"};
constexpr std::size_t kRuns = 1000;

adjoin::SweepSpec spec_for(const std::string& scheme, const std::string& history) {
  const std::string text = "base = \"" ADJOIN_SOURCE_DIR "/records/scenes/paper-strong.toml\"\n"
                           "set = {\"solver.scheme\" = \"" + scheme + "\", \"solver.history\" = \"" + history +
                           "\", \"solver.h\" = 0.002}\n"
                           "[[axis]]\nkey = \"model.mu\"\nfrom = 0.0\nto = 1.0\nn = " + std::to_string(kRuns) + "\n";
  return adjoin::parse_sweep(text, "bench.toml");
}

std::map<std::string, double>& one_thread_rate() {
  static std::map<std::string, double> rates;
  return rates;
}

// Runs/s measured around the one sweep of the benchmark; the 2-thread case also reports the
// parallel efficiency against the 1-thread case of the same scheme and engine (run just before).
void BM_SweepEfficiency(benchmark::State& state) {
  const std::string scheme = kSchemes[state.range(0)], history = kHistories[state.range(1)];
  const auto threads = static_cast<unsigned>(state.range(2));
  const adjoin::SweepSpec spec = spec_for(scheme, history);
  adjoin::SweepOptions options;
  options.jobs = threads;
  double rate = 0.0, cpu = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    const auto rows = adjoin::run_sweep(spec, options);
    benchmark::DoNotOptimize(rows.data());
    rate = static_cast<double>(kRuns) / std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  }
  const std::string key = scheme + "/" + history;
  state.counters["runs/s"] = rate;
  // Runs per CPU-second of the whole process: what the machine would give if nothing else ran.
  state.counters["runs/cpu-s"] = static_cast<double>(kRuns) / cpu;
  if (threads == 1) {
    one_thread_rate()[key] = rate;
  } else if (one_thread_rate().count(key)) {
    state.counters["efficiency"] = rate / (static_cast<double>(threads) * one_thread_rate()[key]);
  }
  state.SetLabel(key + ", " + std::to_string(threads) + " thread" + (threads > 1 ? "s" : ""));
}

}  // namespace

BENCHMARK(BM_SweepEfficiency)
    ->ArgNames({"scheme", "history", "threads"})
    ->ArgsProduct({{0, 1}, {0, 1}, {1, 2}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

BENCHMARK_MAIN();

// Memory of a run against its length: what the outputs keep, apart from the fractional
// history that the solver itself needs (O(N) by nature: every rod force depends on its whole
// past). A run that asks only for the summary keeps O(1) outputs; one that records the time
// series in memory keeps O(N). Counted with a replaced global operator new (peak live bytes).
//
//     build/bench/bench_memory
//
// Prints, for t_end = 16 .. 1024 (8,000 .. 512,000 steps, fft history): peak heap bytes, the
// history engines' bytes, and the rest (outputs and bookkeeping), per run and per step.
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>

#include "adjoin/io/scene.hpp"
#include "adjoin/observe/time_series.hpp"
#include "adjoin/study/run.hpp"

namespace {
std::atomic<long long> live{0}, peak{0};
void note(long long delta) {
  const long long now = live.fetch_add(delta) + delta;
  long long p = peak.load();
  while (now > p && !peak.compare_exchange_weak(p, now)) {}
}
}  // namespace

void* operator new(std::size_t n) {
  void* p = std::malloc(n + 16);
  if (!p) throw std::bad_alloc();
  *static_cast<std::size_t*>(p) = n;
  note(static_cast<long long>(n));
  return static_cast<char*>(p) + 16;
}
void operator delete(void* p) noexcept {
  if (!p) return;
  char* base = static_cast<char*>(p) - 16;
  note(-static_cast<long long>(*reinterpret_cast<std::size_t*>(base)));
  std::free(base);
}
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }

int main() {
  std::printf("%-10s %9s %-16s %14s %14s %14s %12s\n", "t_end", "steps", "outputs", "peak heap [B]", "history [B]",
              "rest [B]", "rest/step");
  for (double t_end : {16.0, 64.0, 256.0, 1024.0}) {
    for (bool keep_series : {false, true}) {
      const adjoin::Scene scene = adjoin::load_scene(
          std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml",
          {"solver.scheme=implicit", "solver.history=fft", "solver.t_end=" + std::to_string(t_end), "output.timeseries=false"});
      adjoin::TimeSeriesRecorder recorder;
      const long long before = live.load();
      peak.store(before);
      const adjoin::RunReport r = adjoin::run_scene(scene, keep_series ? &recorder : nullptr);
      const long long used = peak.load() - before;
      const long long history = static_cast<long long>(r.solver.history_bytes);
      std::printf("%-10g %9zu %-16s %14lld %14lld %14lld %12.1f\n", t_end, r.solver.steps,
                  keep_series ? "summary+series" : "summary only", used, history, used - history,
                  static_cast<double>(used - history) / static_cast<double>(r.solver.steps));
    }
  }
  return 0;
}

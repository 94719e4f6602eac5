// Memory of a run against its length: what the outputs keep, apart from the fractional
// history that the solver itself needs (O(N) by nature: every rod force depends on its whole
// past). A run that asks only for the summary keeps O(1) outputs; one that records the time
// series in memory keeps O(N). Counted with a replaced global operator new (peak live bytes).
//
//     build/bench/bench_memory
//
// Prints, for t_end = 16 .. 1024 (8,000 .. 512,000 steps, fft history): the peak heap of a run
// asking for the summary only (the solver's own history: a constant number of bytes per step,
// plus FFTW's buffers, which operator new does not see) and how much more a run keeps when it
// also records the time series in memory (a ChannelRecorder of every channel: 8 bytes per
// channel per step). A streaming CSV writer
// (adjoin run with output.timeseries) keeps a 64 KiB buffer whatever the length.
//
// The recorder's arrays are Eigen's, which allocates with malloc, not operator new: what a run
// leaves held is read from malloc's own count (glibc's mallinfo2) while the recorder lives.
//
// The quadrature weights are kept for the process (fractional/weights.hpp, at most 64 MB): the
// first run at a length computes them and leaves them cached. Each length is run once first,
// unmeasured, and what that left live is printed ("kept for the process"); the measured runs
// then find the cache as every later run of a study finds it.
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <malloc.h>
#include <new>
#include <string>

#include "adjoin/io/scene.hpp"
#include "adjoin/observe/channel_recorder.hpp"
#include "adjoin/study/run.hpp"

namespace {
long long malloc_held() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<long long>(m.uordblks + m.hblkhd);
}
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
  std::printf("%-8s %9s %22s %16s %26s %14s %22s\n", "t_end", "steps", "peak heap, summary [B]", "per step [B]",
              "extra with series kept [B]", "per step [B]", "kept for the process [B]");
  for (double t_end : {16.0, 64.0, 256.0, 1024.0}) {
    long long used[2] = {0, 0}, held[2] = {0, 0};
    std::size_t steps = 0;
    const adjoin::Scene scene = adjoin::load_scene(
        std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml",
        {"solver.scheme=implicit", "solver.history=fft", "solver.t_end=" + std::to_string(t_end), "output.timeseries=false"});
    const long long start = live.load();
    adjoin::run(scene);  // (leaves this length's weights in the process's cache)
    const long long kept = live.load() - start;
    for (int keep_series = 0; keep_series < 2; ++keep_series) {
      adjoin::ChannelRecorder recorder;
      const long long before = live.load(), held_before = malloc_held();
      peak.store(before);
      const adjoin::Report r = adjoin::run(scene, {keep_series ? &recorder : nullptr});
      used[keep_series] = peak.load() - before;
      held[keep_series] = malloc_held() - held_before;
      steps = r.solver.steps;
    }
    const double n = static_cast<double>(steps);
    std::printf("%-8g %9zu %22lld %16.1f %26lld %14.1f %22lld\n", t_end, steps, used[0], static_cast<double>(used[0]) / n,
                held[1] - held[0], static_cast<double>(held[1] - held[0]) / n, kept);
  }
  return 0;
}

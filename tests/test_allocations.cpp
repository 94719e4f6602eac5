// No heap allocation per step (SPEC §10, issue 24 Part 1): the global operator new is replaced
// in this program by one that counts, and an observer reads the count after a run's first
// steps and at its end. The steps in between (the stepper, the run's own observers) do not
// allocate; what may is the amortized growth of the lists of events a report keeps (a link's
// switching instants, a pair's impacts, the phase intervals: a doubling vector, O(log events)
// allocations in a run) and, with the fft history, the planning of each level of its blocks
// (O(log N)). A per-step allocation would count about N.
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"

// Under a sanitizer the allocator is the sanitizer's: the counting replacement is left out and
// the cases say they are skipped (CTest reports them so).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define ADJOIN_COUNTING_NEW 0
#else
#define ADJOIN_COUNTING_NEW 1
#endif

namespace {

std::atomic<std::size_t> g_allocations{0};

#if ADJOIN_COUNTING_NEW
void* counted(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

void* counted_aligned(std::size_t size, std::align_val_t align) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const auto a = static_cast<std::size_t>(align);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
#endif

}  // namespace

#if ADJOIN_COUNTING_NEW
void* operator new(std::size_t size) { return counted(size); }
void* operator new[](std::size_t size) { return counted(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new(std::size_t size, std::align_val_t align) { return counted_aligned(size, align); }
void* operator new[](std::size_t size, std::align_val_t align) { return counted_aligned(size, align); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
#endif

namespace {

using namespace adjoin;

// The allocation count after `warm_up` grid points and at the run's end.
class AllocationWatch final : public StructureObserver {
 public:
  explicit AllocationWatch(std::size_t warm_up) : warm_up_(warm_up) {}
  void observe(const StructureState&) override {
    if (++points_ == warm_up_) at_warm_up = g_allocations.load();
  }
  void end() override { at_end = g_allocations.load(); }
  std::size_t during() const { return at_end - at_warm_up; }
  std::size_t points() const { return points_; }
  std::size_t at_warm_up = 0, at_end = 0;

 private:
  std::size_t warm_up_, points_ = 0;
};

const std::string kScenes = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/";

std::size_t allocations_during(const std::string& file, const std::vector<std::string>& keys, std::size_t* points) {
  if (!ADJOIN_COUNTING_NEW) {
    std::puts("ADJOIN_TEST_SKIPPED: allocations are not counted under a sanitizer");
    *points = 1001;
    return 0;
  }
  const Scene scene = load_scene(file, keys);
  AllocationWatch watch(20);
  run(scene, {&watch});
  *points = watch.points();
  return watch.during();
}

}  // namespace

TEST_CASE("the two-frame building run does not allocate per step", "[allocations]") {
  for (const char* history : {"soe", "direct"}) {
    INFO(history);
    std::size_t points = 0;
    const std::size_t n = allocations_during(kScenes + "buildings/two-frames.toml",
                                             {std::string("solver.history=") + history, "solver.t_end=10",
                                              "solver.error_estimate=false"},
                                             &points);
    REQUIRE(points > 1000);
    CHECK(static_cast<double>(n) <= 2.0 * std::log2(static_cast<double>(points)));
  }
}

TEST_CASE("with the fft history a run allocates only a few times per level of its blocks", "[allocations]") {
  std::size_t points = 0;
  const std::size_t n = allocations_during(kScenes + "buildings/two-frames.toml",
                                           {"solver.history=fft", "solver.t_end=10", "solver.error_estimate=false"}, &points);
  REQUIRE(points > 1000);
  // log2 of the steps levels, each planned once with its few buffers, for each Zener order.
  CHECK(static_cast<double>(n) <= 16.0 * std::log2(static_cast<double>(points)));
}

TEST_CASE("a two-block run on the structure stepper does not allocate per step", "[allocations]") {
  for (const char* scheme : {"implicit", "implicit-damped"}) {
    INFO(scheme);
    std::size_t points = 0;
    const std::size_t n = allocations_during(kScenes + "paper-strong.toml",
                                             {std::string("solver.scheme=") + scheme, "solver.history=soe",
                                              "solver.error_estimate=false"},
                                             &points);
    REQUIRE(points > 1000);
    CHECK(static_cast<double>(n) <= 2.0 * std::log2(static_cast<double>(points)));
  }
}

// The long stress case: t_end = 1e4 at h = 0.002 with the fft history engine (5,000,000
// steps). Labelled "slow" (the sanitizer build skips it).
#include <catch2/catch.hpp>
#include <cmath>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"

using namespace adjoin;

TEST_CASE("5,000,000 steps with the fft engine: finite, the strong scene's story, energy balanced", "[stress][slow]") {
  const std::string dir = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/";
  const Scene scene = load_scene(dir + "stress/long-1e4.toml");
  REQUIRE(scene.solver.steps() >= 5000000);
  REQUIRE(scene.solver.history == HistoryEngine::fft);
  const Report r = run(scene);
  // The first 16 time units are the strong scene: the same peaks as a short direct run.
  const Report short_run = run(load_scene(dir + "paper-strong.toml", {"solver.scheme=implicit"}));
  CHECK(r.peak("A.x1").max_abs == Approx(short_run.peak("A.x1").max_abs).epsilon(1e-12));
  CHECK(r.phases.size() == short_run.phases.size());
  // After the excitation has died away the blocks are stuck and at rest to rounding.
  CHECK(r.phases.back().state == Phase::stick);
  CHECK(std::abs(r.last_value("A.v1")) < 1e-6);
  CHECK(std::isfinite(r.last_value("A.x1")));
  CHECK(std::abs(r.energy.residual) < 1e-5 * r.energy.input);
}

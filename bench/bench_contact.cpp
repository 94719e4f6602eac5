// Pounding's cost (SPEC §6): the paper's strong scene with xi0 = 0.3 (it pounds twice) and each
// contact law, against the same scene without a contact law (the two-block implicit scheme,
// which lets the blocks pass through each other), at the scene's step h = 0.002:
//
//     build/bench/bench_contact --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//
// The structure step is not refined during contact: each pair's motion through the step is
// integrated on its own (solver/contact_step.hpp), so a stiffer contact costs more sub-steps
// of a scalar problem only; stiff/ runs the linear law 10^3 and 10^6 times stiffer.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "adjoin/io/scene.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/structure/observer.hpp"

namespace {

using namespace adjoin;

class Nothing final : public StructureObserver {
 public:
  void observe(const StructureState& s) override { benchmark::DoNotOptimize(s.x[0]); }
};

void run(benchmark::State& state, const std::vector<std::string>& law) {
  std::vector<std::string> keys(law);
  keys.emplace_back("solver.scheme=implicit");
  bool gap = false;
  for (const std::string& k : law) gap = gap || k.rfind("model.gap0", 0) == 0;
  if (!gap) keys.emplace_back("model.gap0=0.3");
  const Scene scene = load_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml", keys);
  Nothing observer;
  for (auto _ : state) simulate_as_structure(two_block_options(scene), scene.structure, *scene.ground, observer);
}

const std::vector<std::string> kLinear{"model.contact.model=linear", "model.contact.stiffness=1000", "model.contact.restitution=0.65"};

}  // namespace

BENCHMARK_CAPTURE(run, none, {});
// The structure solver that runs a two-block scene with a contact law, on a gap never closed.
BENCHMARK_CAPTURE(run, impact_never_touching, {"model.gap0=100", "model.contact.model=impact", "model.contact.restitution=0.65"});
BENCHMARK_CAPTURE(run, linear, kLinear);
BENCHMARK_CAPTURE(run, hertz, {"model.contact.model=hertz", "model.contact.stiffness=1000"});
BENCHMARK_CAPTURE(run, hertzdamp, {"model.contact.model=hertzdamp", "model.contact.stiffness=1000", "model.contact.restitution=0.65"});
BENCHMARK_CAPTURE(run, jankowski, {"model.contact.model=jankowski", "model.contact.stiffness=1000", "model.contact.restitution=0.65"});
BENCHMARK_CAPTURE(run, impact, {"model.contact.model=impact", "model.contact.restitution=0.65"});
BENCHMARK_CAPTURE(run, stiff_linear_1e6, {"model.contact.model=linear", "model.contact.stiffness=1e6", "model.contact.restitution=0.65"});
BENCHMARK_CAPTURE(run, stiff_linear_1e9, {"model.contact.model=linear", "model.contact.stiffness=1e9", "model.contact.restitution=0.65"});

BENCHMARK_MAIN();

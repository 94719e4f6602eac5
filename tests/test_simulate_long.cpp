// solver/simulate, the long case: the up-front memory estimate bounds what runs of up to
// 128,000 steps with the direct history really hold. Labelled "slow" (the sanitizer build skips
// it: its quadratic direct sums take two minutes there and check no memory access the short
// cases of test_simulate do not).
#include <catch2/catch.hpp>

#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/structure/observer.hpp"
#include "adjoin/solver/simulate.hpp"

using namespace adjoin;

namespace {

// Watches nothing: the run alone is measured.
class Nothing final : public StructureObserver {
 public:
  void observe(const StructureState&) override {}
};

}  // namespace

TEST_CASE("estimated_history_bytes bounds the measured history within a factor 1.5", "[simulate][memory][slow]") {
  const DecayingSine ground(1.5, 1.5, 0.5);
  Nothing none;
  for (Scheme scheme : {Scheme::paper, Scheme::implicit})
    for (HistoryEngine engine : {HistoryEngine::direct, HistoryEngine::fft})
      for (double t_end : {16.0, 64.0}) {
        SolverOptions o;
        o.scheme = scheme;
        o.history = engine;
        o.h = scheme == Scheme::paper ? 0.0005 : 0.001;
        o.t_end = t_end;
        Model model = Model::Paper();
        const double estimate = estimated_history_bytes(o, model);
        const auto measured = static_cast<double>(simulate_as_structure(o, model, ground, none).history_bytes);
        INFO(to_string(scheme) << "/" << to_string(engine) << ", " << o.steps() << " steps: estimate " << estimate
                               << " B, measured " << measured << " B");
        CHECK(measured > 0.0);
        CHECK(estimate >= measured);
        CHECK(estimate <= 1.5 * measured);
      }
}

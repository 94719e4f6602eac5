// solver/simulate: the two-block solver's entry points (a model or its 1 + 1 structure), and the
// up-front memory estimate that bounds what the run really holds, so a run too large for the
// machine can be refused before it starts.
#include <catch2/catch.hpp>

#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/structure/observer.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/structure/two_block.hpp"
#include "state_recorder.hpp"

using namespace adjoin;

namespace adjoin::test {

// Watches nothing: the run alone is measured.
class Nothing final : public StructureObserver {
 public:
  void observe(const StructureState&) override {}
};

}  // namespace adjoin::test

using test::Nothing;

TEST_CASE("elastic rods hold no history, and the estimate says so", "[simulate][memory]") {
  SolverOptions o;
  o.t_end = 8.0;
  Model model = Model::Paper();
  model.rod1 = Rod::Elastic();
  model.rod2 = Rod::Elastic();
  Nothing none;
  const auto measured = simulate_as_structure(o, model, DecayingSine(1.5, 1.5, 0.5), none).history_bytes;
  CHECK(measured < 4096);
  CHECK(estimated_history_bytes(o, model) <= 4096.0);
  CHECK(estimated_history_bytes(o, model) >= static_cast<double>(measured));
}

TEST_CASE("physical_memory_bytes reads the machine", "[simulate][memory]") {
  const double bytes = physical_memory_bytes();
  CHECK(bytes > 1e8);   // more than 100 MB
  CHECK(bytes < 1e14);  // less than 100 TB
}

TEST_CASE("the two-block solver runs a model's 1 + 1 structure as it runs the model", "[simulate]") {
  Model model = Model::Paper();
  model.rho = 0.41;  // 1 / (1 / 0.41) != 0.41: the paper scheme runs the model read back
  const DecayingSine ground(1.5, 1.5, 0.5);
  const structure::Structure s = structure::two_block_structure(model);
  for (const Scheme scheme : {Scheme::paper, Scheme::implicit, Scheme::implicit_damped}) {
    SolverOptions o;
    o.scheme = scheme;
    o.t_end = 4.0;
    o.h = 0.01;
    test::StateRecorder by_model, by_structure;
    simulate_as_structure(o, model, ground, by_model);
    simulate_as_structure(o, s, ground, by_structure);
    REQUIRE(by_model.states.size() == by_structure.states.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < by_model.states.size(); ++i)
      worst = std::max({worst, std::abs(by_model.states[i].x[0] - by_structure.states[i].x[0]),
                        std::abs(by_model.states[i].x[1] - by_structure.states[i].x[1])});
    INFO(to_string(scheme));
    // the implicit schemes run the very structure; the paper scheme a model equal but for rho's rounding
    CHECK(worst <= (scheme == Scheme::paper ? 1e-12 : 0.0));
  }
}

TEST_CASE("the two-block solver refuses a structure that is not a model's, saying why", "[simulate]") {
  structure::Structure s = structure::two_block_structure(Model::Paper());
  s.b->masses.resize(2);
  s.b->masses << 1.0, 1.0;
  Nothing none;
  SolverOptions o;
  o.t_end = 1.0;
  try {
    simulate_as_structure(o, s, DecayingSine(1.5, 1.5, 0.5), none);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("building B has 2 floors, not 1") != std::string::npos);
  }
}

// solver/simulate: the up-front memory estimate bounds what the run really holds, so a run too
// large for the machine can be refused before it starts.
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

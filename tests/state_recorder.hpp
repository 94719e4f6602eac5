#pragma once
// Every state of a structure run (or every `every`-th grid point and the last), kept in
// memory: the tests' trajectory recorder. A two-block run's states are its 1 + 1 structure's
// (structure/two_block.hpp), in the scene's dimensionless units: x[0], x[1] the blocks,
// storey_force[0], [1] the rods, link 0 the damper (when mu > 0), then the base sliders.
#include <cstddef>
#include <vector>

#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/observer.hpp"

namespace adjoin::test {

class StateRecorder final : public StructureObserver {
 public:
  explicit StateRecorder(std::size_t every = 1) : every_(every == 0 ? 1 : every) {}
  void begin(const structure::Structure&, const StructureSolverOptions& o) override {
    states.clear();
    steps_ = o.steps();
    count_ = 0;
  }
  void observe(const StructureState& s) override {
    if (count_ % every_ == 0 || count_ == steps_) states.push_back(s);
    ++count_;
  }
  std::vector<StructureState> states;

 private:
  std::size_t every_;
  std::size_t steps_ = 0, count_ = 0;
};

}  // namespace adjoin::test
